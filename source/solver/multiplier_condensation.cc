#include <glide/solver/multiplier_condensation.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <stdexcept>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /**
     * An orthonormal frame [n t_1 (t_2)] of the unit vector @p n, as
     * frame[l][k] (component l of direction k). A coordinate axis that is
     * normal to n (a symmetry plane: its DoF is constrained and has no
     * force) is taken as a tangent itself, so that the rotation does not
     * mix a constrained row into the others.
     */
    std::vector<std::vector<double>>
    frame_of(const std::vector<double> &n)
    {
      const unsigned int               dim = n.size();
      std::vector<std::vector<double>> q(dim, std::vector<double>(dim, 0.));
      for (unsigned int l = 0; l < dim; ++l)
        q[l][0] = n[l];
      if (dim == 1)
        return q;
      if (dim == 2)
        {
          q[0][1] = -n[1];
          q[1][1] = n[0];
          return q;
        }
      // 3D: t_1 a coordinate axis normal to n if there is one, otherwise
      // the axis least aligned with n made normal to it; t_2 = n x t_1.
      unsigned int axis = 0;
      for (unsigned int l = 1; l < 3; ++l)
        if (std::abs(n[l]) < std::abs(n[axis]))
          axis = l;
      std::vector<double> t1(3, 0.);
      t1[axis] = 1.;
      if (n[axis] != 0.)
        {
          double norm = 0.;
          for (unsigned int l = 0; l < 3; ++l)
            {
              t1[l] -= n[axis] * n[l];
              norm += t1[l] * t1[l];
            }
          for (auto &v : t1)
            v /= std::sqrt(norm);
        }
      const std::vector<double> t2 = {n[1] * t1[2] - n[2] * t1[1],
                                      n[2] * t1[0] - n[0] * t1[2],
                                      n[0] * t1[1] - n[1] * t1[0]};
      for (unsigned int l = 0; l < 3; ++l)
        {
          q[l][1] = t1[l];
          q[l][2] = t2[l];
        }
      return q;
    }
  } // namespace

  MultiplierCondensation::MultiplierCondensation(
    std::vector<Block>            blocks_in,
    const types::global_dof_index n_displacements,
    const IndexSet               &owned_in,
    MPI_Comm                      comm_in)
    : blocks(std::move(blocks_in))
    , n_u(n_displacements)
    , owned(owned_in)
    , comm(comm_in)
  {
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      throw std::logic_error(
        "MultiplierCondensation: one process only (issue 15)");
    owned_displacements = owned.get_view(0, n_u);
    block_of.assign(n_u, -1);
    component_of.assign(n_u, 0);
    for (unsigned int j = 0; j < blocks.size(); ++j)
      {
        if (blocks[j].multiplier != n_u + j)
          throw std::logic_error(
            "MultiplierCondensation: multipliers must be numbered in the "
            "order of the blocks, from the first one after the "
            "displacements on");
        for (unsigned int l = 0; l < blocks[j].dofs.size(); ++l)
          {
            const auto d = blocks[j].dofs[l];
            if (block_of[d] != -1)
              throw std::logic_error(
                "MultiplierCondensation: a DoF in two blocks");
            block_of[d]     = j;
            component_of[d] = l;
          }
      }
    states.resize(blocks.size());
    map = std::make_unique<Epetra_Map>(
      owned_displacements.make_trilinos_map(comm, false));
  }

  MultiplierCondensation::~MultiplierCondensation() = default;

  void
  MultiplierCondensation::row_of_j(
    const types::global_dof_index         row,
    int                                  &n,
    double                              *&values,
    std::vector<types::global_dof_index> &columns) const
  {
    const auto &A   = J->trilinos_matrix();
    int        *idx = nullptr;
    A.ExtractMyRowView(A.RowMap().LID(static_cast<int>(row)), n, values, idx);
    columns.resize(n);
    for (int e = 0; e < n; ++e)
      columns[e] = A.ColMap().GID(idx[e]);
  }

  template <typename Add>
  void
  MultiplierCondensation::condensed_row(const types::global_dof_index row,
                                        Add                         &&add) const
  {
    const auto &A = J->trilinos_matrix();
    // Rows through their local views: for_each(row, f) calls f(column,
    // value) for every entry of row @p row of J.
    const auto for_each = [&A](const types::global_dof_index r, const auto &f) {
      int     n      = 0;
      double *values = nullptr;
      int    *idx    = nullptr;
      A.ExtractMyRowView(A.RowMap().LID(static_cast<int>(r)), n, values, idx);
      for (int e = 0; e < n; ++e)
        f(static_cast<types::global_dof_index>(A.ColMap().GID(idx[e])),
          values[e]);
    };
    // Columns of closed nodes in their frames: the unknown of direction k
    // of the node is sum_l frame[l][k] du_l.
    const auto emit = [&](const types::global_dof_index c, const double v) {
      if (c >= n_u)
        return;
      const int jb = block_of[c];
      if (jb >= 0 && states[jb].closed)
        {
          const auto &q = states[jb].frame[component_of[c]];
          for (unsigned int k = 0; k < q.size(); ++k)
            if (q[k] != 0.)
              add(blocks[jb].dofs[k], v * q[k]);
        }
      else
        add(c, v);
    };

    const int jb = block_of[row];
    if (jb >= 0 && states[jb].closed)
      {
        const auto        &s = states[jb];
        const unsigned int k = component_of[row];
        if (k == 0) // the constraint row
          for_each(blocks[jb].multiplier,
                   [&](const auto c, const double v) { emit(c, s.scale * v); });
        else // tangential row k: t_k^T A_S
          for (unsigned int l = 0; l < s.frame.size(); ++l)
            if (s.frame[l][k] != 0.)
              for_each(blocks[jb].dofs[l],
                       [&, q = s.frame[l][k]](const auto c, const double v) {
                         emit(c, q * v);
                       });
        return;
      }
    for_each(row, [&](const auto c, const double v) {
      if (c < n_u)
        emit(c, v);
      else if (v != 0.)
        {
          // A closed multiplier reaching this row (a master node):
          // -B_ij b_j^T A_S / |b_j|^2.
          const auto &s = states[c - n_u];
          if (!s.closed)
            return;
          for (unsigned int l = 0; l < s.b.size(); ++l)
            if (s.b[l] != 0.)
              for_each(blocks[c - n_u].dofs[l],
                       [&, w = -v * s.b[l] / s.b_norm2](const auto   c2,
                                                        const double v2) {
                         emit(c2, w * v2);
                       });
        }
    });
  }

  void
  MultiplierCondensation::condense(const TrilinosWrappers::SparseMatrix &J_in)
  {
    J = &J_in;
    std::vector<types::global_dof_index> columns;
    int                                  n      = 0;
    double                              *values = nullptr;
    for (unsigned int j = 0; j < blocks.size(); ++j)
      {
        const auto &block = blocks[j];
        State      &s     = states[j];
        const auto  m     = block.multiplier;
        double      E     = 0.;
        double      C     = 0.;
        row_of_j(m, n, values, columns);
        for (int e = 0; e < n; ++e)
          if (columns[e] == m)
            E = values[e];
          else
            C = std::max(C, std::abs(values[e]));
        s.closed = (E == 0.);
        if (!s.closed && C != 0.)
          throw std::logic_error("MultiplierCondensation: an open multiplier "
                                 "row with displacement entries");
        s.open_diagonal = E;
        s.b.assign(block.dofs.size(), 0.);
        s.b_norm2 = 0.;
        for (unsigned int l = 0; l < block.dofs.size(); ++l)
          {
            row_of_j(block.dofs[l], n, values, columns);
            for (int e = 0; e < n; ++e)
              if (columns[e] == m)
                s.b[l] = values[e];
              else if (columns[e] >= n_u && values[e] != 0.)
                throw std::logic_error(
                  "MultiplierCondensation: a slave node's rows hold the "
                  "force of another node's multiplier");
            s.b_norm2 += s.b[l] * s.b[l];
          }
        if (!s.closed)
          continue;
        if (s.b_norm2 == 0.)
          throw std::runtime_error(
            "a closed slave node whose displacements are all constrained "
            "cannot be condensed; use 'Linear solver/Type = direct'");
        std::vector<double> normal(s.b);
        for (auto &v : normal)
          v /= std::sqrt(s.b_norm2);
        s.frame = frame_of(normal);
        // The constraint row's entry in the normal direction of the node:
        // c dg/du . n, negative for the usual sign of the gap, of the size
        // of the pair's contact modulus c.
        double diagonal = 0.;
        row_of_j(m, n, values, columns);
        for (int e = 0; e < n; ++e)
          if (columns[e] < n_u && block_of[columns[e]] == static_cast<int>(j))
            diagonal += values[e] * s.frame[component_of[columns[e]]][0];
        if (diagonal == 0.)
          throw std::runtime_error(
            "a closed slave node's constraint does not involve its normal "
            "displacement; use 'Linear solver/Type = direct'");
        // The row is scaled (an exact operation on an equation) so that
        // its diagonal is the node's normal stiffness n^T A_SS n: AMG then
        // sees the normal unknown of a closed node as stiff as its
        // tangential ones, whatever the ratio of c to the slave's modulus.
        // With the row of size c, a slave 1e6 times stiffer than its master
        // (c the soft side's modulus) kept GMRES + AMG from converging in
        // 2000 iterations, and the load steps were cut back. Where
        // n^T A_SS n is not positive (possible at finite strain), only the
        // sign is turned.
        double normal_stiffness = 0.;
        for (unsigned int l = 0; l < block.dofs.size(); ++l)
          {
            row_of_j(block.dofs[l], n, values, columns);
            for (int e = 0; e < n; ++e)
              if (columns[e] < n_u &&
                  block_of[columns[e]] == static_cast<int>(j))
                normal_stiffness +=
                  normal[l] * values[e] * normal[component_of[columns[e]]];
          }
        s.scale = normal_stiffness > 0. ? normal_stiffness / diagonal :
                  diagonal > 0.         ? 1. :
                                          -1.;
      }

    condensed.reset(); // before its successor is built (peak memory)
    // Two passes over the rows: the number of distinct columns (Epetra's
    // static profile), then the values.
    const unsigned int n_rows = owned_displacements.n_elements();
    std::vector<int>   counts(n_rows, 0);
    std::vector<types::global_dof_index> stamp(n_u, numbers::invalid_dof_index);
    unsigned int                         r = 0;
    for (const auto row : owned_displacements)
      {
        condensed_row(row, [&](const types::global_dof_index c, const double) {
          if (stamp[c] != row)
            {
              stamp[c] = row;
              ++counts[r];
            }
        });
        ++r;
      }
    condensed =
      std::make_unique<Epetra_CrsMatrix>(Copy, *map, counts.data(), true);
    std::vector<double> work(n_u, 0.);
    std::vector<int>    touched;
    std::vector<double> row_values;
    for (const auto row : owned_displacements)
      {
        touched.clear();
        condensed_row(row,
                      [&](const types::global_dof_index c, const double v) {
                        if (stamp[c] != n_u + row)
                          {
                            stamp[c] = n_u + row;
                            touched.push_back(c);
                            work[c] = 0.;
                          }
                        work[c] += v;
                      });
        row_values.resize(touched.size());
        for (unsigned int e = 0; e < touched.size(); ++e)
          row_values[e] = work[touched[e]];
        condensed->InsertGlobalValues(static_cast<int>(row),
                                      touched.size(),
                                      row_values.data(),
                                      touched.data());
      }
    condensed->FillComplete(*map, *map);

    // What condense_rhs() and expand() need of J, so that J itself can be
    // released until the next Jacobian (LinearSolver::keeps_matrix()): the
    // multiplier entries of the rows of open nodes and master nodes, and
    // the displacement part of the rows of closed nodes.
    couplings.clear();
    for (const auto row : owned_displacements)
      {
        const int jb = block_of[row];
        if (jb >= 0 && states[jb].closed)
          continue;
        row_of_j(row, n, values, columns);
        for (int e = 0; e < n; ++e)
          if (columns[e] >= n_u && values[e] != 0.)
            couplings.push_back(
              {row, static_cast<unsigned int>(columns[e] - n_u), values[e]});
      }
    closed_rows.assign(blocks.size(), {});
    for (unsigned int j = 0; j < blocks.size(); ++j)
      if (states[j].closed)
        for (const auto d : blocks[j].dofs)
          {
            row_of_j(d, n, values, columns);
            std::vector<std::pair<types::global_dof_index, double>> entries;
            for (int e = 0; e < n; ++e)
              if (columns[e] < n_u)
                entries.emplace_back(columns[e], values[e]);
            closed_rows[j].push_back(std::move(entries));
          }
    J = nullptr;
  }

  std::unique_ptr<Epetra_MultiVector>
  MultiplierCondensation::rotated_modes(
    const std::vector<TrilinosWrappers::MPI::Vector> &modes) const
  {
    auto rotated = std::make_unique<Epetra_MultiVector>(*map, modes.size());
    for (unsigned int m = 0; m < modes.size(); ++m)
      for (int i = 0; i < map->NumMyElements(); ++i)
        {
          const types::global_dof_index row = map->GID(i);
          const int                     jb  = block_of[row];
          if (jb >= 0 && states[jb].closed)
            {
              // Q^T u_S: the mode's component along direction k.
              const auto        &block = blocks[jb];
              const unsigned int k     = component_of[row];
              double             v     = 0.;
              for (unsigned int l = 0; l < block.dofs.size(); ++l)
                v += states[jb].frame[l][k] * modes[m](block.dofs[l]);
              (*rotated)[m][i] = v;
            }
          else
            (*rotated)[m][i] = modes[m](row);
        }
    return rotated;
  }

  void
  MultiplierCondensation::condense_rhs(
    const TrilinosWrappers::MPI::Vector &b,
    TrilinosWrappers::MPI::Vector       &condensed_b) const
  {
    condensed_b.reinit(owned_displacements, comm);
    for (const auto row : owned_displacements)
      {
        const int jb = block_of[row];
        double    v  = 0.;
        if (jb >= 0 && states[jb].closed)
          {
            const auto &s = states[jb];
            const auto  k = component_of[row];
            if (k == 0)
              v = s.scale * b(blocks[jb].multiplier);
            else
              for (unsigned int l = 0; l < s.frame.size(); ++l)
                v += s.frame[l][k] * b(blocks[jb].dofs[l]);
          }
        else
          v = b(row);
        condensed_b(row) = v;
      }
    // The multipliers in the other rows: closed ones through the slave
    // node's rows, open ones known.
    for (const auto &c : couplings)
      {
        const auto &s     = states[c.block];
        const auto &block = blocks[c.block];
        if (s.closed)
          {
            double bf = 0.;
            for (unsigned int l = 0; l < s.b.size(); ++l)
              bf += s.b[l] * b(block.dofs[l]);
            condensed_b(c.row) -= c.value * bf / s.b_norm2;
          }
        else
          condensed_b(c.row) -= c.value * b(block.multiplier) / s.open_diagonal;
      }
    condensed_b.compress(VectorOperation::insert);
  }

  void
  MultiplierCondensation::expand(const TrilinosWrappers::MPI::Vector &b,
                                 const TrilinosWrappers::MPI::Vector &xc,
                                 TrilinosWrappers::MPI::Vector       &x) const
  {
    // du: the condensed unknowns, closed nodes rotated back (du_S = Q x_S).
    std::vector<double> du(n_u, 0.);
    for (const auto row : owned_displacements)
      {
        const int jb = block_of[row];
        if (jb >= 0 && states[jb].closed)
          {
            const auto &block = blocks[jb];
            for (unsigned int k = 0; k < block.dofs.size(); ++k)
              du[row] +=
                states[jb].frame[component_of[row]][k] * xc(block.dofs[k]);
          }
        else
          du[row] = xc(row);
      }
    for (const auto row : owned_displacements)
      x(row) = du[row];
    for (unsigned int j = 0; j < blocks.size(); ++j)
      {
        const auto &s     = states[j];
        const auto &block = blocks[j];
        if (!s.closed)
          {
            x(block.multiplier) = b(block.multiplier) / s.open_diagonal;
            continue;
          }
        // dl_j = b_j^T (f_S - A_S du) / |b_j|^2.
        double v = 0.;
        for (unsigned int l = 0; l < block.dofs.size(); ++l)
          {
            double r = b(block.dofs[l]);
            for (const auto &[column, value] : closed_rows[j][l])
              r -= value * du[column];
            v += s.b[l] * r;
          }
        x(block.multiplier) = v / s.b_norm2;
      }
    x.compress(VectorOperation::insert);
  }

  unsigned int
  MultiplierCondensation::n_closed() const
  {
    unsigned int n = 0;
    for (const auto &s : states)
      n += s.closed ? 1 : 0;
    return n;
  }
} // namespace glide
