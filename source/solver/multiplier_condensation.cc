#include <glide/base/collective_failure.h>
#include <glide/solver/multiplier_condensation.h>

#include <deal.II/base/mpi.h>

#include <Epetra_Import.h>
#include <Epetra_Map.h>

#include <algorithm>
#include <cmath>
#include <set>
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
    std::vector<Block>            own_blocks,
    const types::global_dof_index n_displacements,
    const IndexSet               &owned_in,
    MPI_Comm                      comm_in)
    : n_u(n_displacements)
    , owned(owned_in)
    , comm(comm_in)
    , parallel(Utilities::MPI::n_mpi_processes(comm_in) > 1)
  {
    owned_displacements = owned.get_view(0, n_u);
    // Every process learns every block (its multiplier and its node's
    // DoFs): a master row may hold the multiplier of a slave node of
    // another process, and a row's columns may be such nodes. The blocks
    // of each process follow those of the lower ranks, as the multipliers
    // are numbered (Contact::setup).
    const unsigned int n_own = own_blocks.size();
    first_own                = 0;
    if (parallel)
      {
        std::vector<types::global_dof_index> packed;
        for (const auto &block : own_blocks)
          {
            packed.push_back(block.multiplier);
            packed.push_back(block.dofs.size());
            packed.insert(packed.end(), block.dofs.begin(), block.dofs.end());
          }
        const auto all  = Utilities::MPI::all_gather(comm, packed);
        const auto rank = Utilities::MPI::this_mpi_process(comm);
        for (unsigned int p = 0; p < all.size(); ++p)
          {
            if (p == rank)
              first_own = blocks.size();
            for (std::size_t i = 0; i < all[p].size();)
              {
                Block      block{all[p][i], {}};
                const auto n = all[p][i + 1];
                block.dofs.assign(all[p].begin() + i + 2,
                                  all[p].begin() + i + 2 + n);
                blocks.push_back(std::move(block));
                i += 2 + n;
              }
          }
      }
    else
      blocks = std::move(own_blocks);
    end_own = first_own + n_own;
    block_of.assign(n_u, -1);
    component_of.assign(n_u, 0);
    // Checks of the caller's numbering; one process's failure is thrown on
    // every process (the Epetra map below is collective).
    std::string failure;
    for (unsigned int j = 0; j < blocks.size() && failure.empty(); ++j)
      {
        if (blocks[j].multiplier != n_u + j)
          failure = "MultiplierCondensation: multipliers must be numbered "
                    "in the order of the blocks, from the first one after "
                    "the displacements on";
        for (unsigned int l = 0; l < blocks[j].dofs.size(); ++l)
          {
            const auto d = blocks[j].dofs[l];
            if (block_of[d] != -1)
              failure = "MultiplierCondensation: a DoF in two blocks";
            block_of[d]     = j;
            component_of[d] = l;
            // A node's DoFs are owned with its multiplier (one process
            // owns all DoFs of a vertex, and the multiplier is numbered by
            // the process that owns the slave node).
            if (owned.is_element(d) != (j >= first_own && j < end_own))
              failure = "MultiplierCondensation: a slave node's DoFs and "
                        "its multiplier are owned by different processes";
          }
      }
    throw_first_failure<std::logic_error>(failure, comm);
    states.resize(blocks.size());
    map = std::make_unique<Epetra_Map>(
      owned_displacements.make_trilinos_map(comm, false));
  }

  MultiplierCondensation::~MultiplierCondensation() = default;

  void
  MultiplierCondensation::row_view(const types::global_dof_index row,
                                   int                          &n,
                                   double                      *&values,
                                   int                         *&idx,
                                   const Epetra_BlockMap       *&columns) const
  {
    const auto &A   = J->trilinos_matrix();
    int         lid = A.RowMap().LID(static_cast<int>(row));
    if (lid >= 0)
      {
        A.ExtractMyRowView(lid, n, values, idx);
        columns = &A.ColMap();
        return;
      }
    lid = remote ? remote->RowMap().LID(static_cast<int>(row)) : -1;
    if (lid < 0)
      throw std::logic_error("MultiplierCondensation: row " +
                             std::to_string(row) +
                             " is neither owned nor imported");
    remote->ExtractMyRowView(lid, n, values, idx);
    columns = &remote->ColMap();
  }

  void
  MultiplierCondensation::row_of_j(
    const types::global_dof_index         row,
    int                                  &n,
    double                              *&values,
    std::vector<types::global_dof_index> &columns) const
  {
    int                   *idx            = nullptr;
    const Epetra_BlockMap *map_of_columns = nullptr;
    row_view(row, n, values, idx, map_of_columns);
    columns.resize(n);
    for (int e = 0; e < n; ++e)
      columns[e] = map_of_columns->GID(idx[e]);
  }

  template <typename Add>
  void
  MultiplierCondensation::condensed_row(const types::global_dof_index row,
                                        Add                         &&add) const
  {
    // Rows through their local views (of J, or of the rows imported from
    // other processes): for_each(row, f) calls f(column, value) for every
    // entry of row @p row of J.
    const auto for_each = [this](const types::global_dof_index r,
                                 const auto                   &f) {
      int                    n      = 0;
      double                *values = nullptr;
      int                   *idx    = nullptr;
      const Epetra_BlockMap *cmap   = nullptr;
      row_view(r, n, values, idx, cmap);
      for (int e = 0; e < n; ++e)
        f(static_cast<types::global_dof_index>(cmap->GID(idx[e])), values[e]);
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
          if (s.compliant)
            {
              // -B_ij C_j / E_jj (penalty).
              for_each(blocks[c - n_u].multiplier,
                       [&, w = -v / s.open_diagonal](const auto   c2,
                                                     const double v2) {
                         if (c2 < n_u)
                           emit(c2, w * v2);
                       });
              return;
            }
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
  MultiplierCondensation::compute_state(const unsigned int j)
  {
    std::vector<types::global_dof_index> columns;
    int                                  n      = 0;
    double                              *values = nullptr;
    const auto                          &block  = blocks[j];
    State                               &s      = states[j];
    const auto                           m      = block.multiplier;
    double                               E      = 0.;
    double                               C      = 0.;
    row_of_j(m, n, values, columns);
    for (int e = 0; e < n; ++e)
      if (columns[e] == m)
        E = values[e];
      else
        C = std::max(C, std::abs(values[e]));
    s.closed        = (E == 0.);
    s.compliant     = !s.closed && C != 0.;
    s.open_diagonal = E;
    s.b.assign(block.dofs.size(), 0.);
    s.b_norm2 = 0.;
    s.frame.clear();
    s.scale = 1.;
    s.foreign.assign(block.dofs.size(), {});
    for (unsigned int l = 0; l < block.dofs.size(); ++l)
      {
        row_of_j(block.dofs[l], n, values, columns);
        for (int e = 0; e < n; ++e)
          if (columns[e] == m)
            s.b[l] = values[e];
          else if (columns[e] >= n_u && values[e] != 0.)
            // The force of a hanging slave node constrained to this one
            // (checked to be open once all states are known).
            s.foreign[l].emplace_back(columns[e] - n_u, values[e]);
        s.b_norm2 += s.b[l] * s.b[l];
      }
    if (!s.closed)
      return;
    if (s.b_norm2 == 0.)
      throw NotCondensable(
        "a slave node in contact has no rows of its own (a hanging node of "
        "a refined slave surface, or a node whose displacements are all "
        "prescribed)");
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
          if (columns[e] < n_u && block_of[columns[e]] == static_cast<int>(j))
            normal_stiffness +=
              normal[l] * values[e] * normal[component_of[columns[e]]];
      }
    s.scale = normal_stiffness > 0. ? normal_stiffness / diagonal :
              diagonal > 0.         ? 1. :
                                      -1.;
  }

  void
  MultiplierCondensation::share_states()
  {
    // Packed per block: closed, E_jj, scale, |b|^2, b, and if closed the
    // frame and, per DoF, the number of foreign entries and the entries
    // (block, value): a master row that holds a closed multiplier reads
    // them (condense_rhs()).
    std::vector<double> packed;
    for (unsigned int j = first_own; j < end_own; ++j)
      {
        const auto &s = states[j];
        packed.insert(packed.end(),
                      {s.closed    ? 1. :
                       s.compliant ? 2. :
                                     0.,
                       s.open_diagonal,
                       s.scale,
                       s.b_norm2});
        packed.insert(packed.end(), s.b.begin(), s.b.end());
        if (s.closed)
          {
            for (const auto &row : s.frame)
              packed.insert(packed.end(), row.begin(), row.end());
            for (const auto &entries : s.foreign)
              {
                packed.push_back(entries.size());
                for (const auto &[k, value] : entries)
                  packed.insert(packed.end(), {double(k), value});
              }
          }
      }
    const auto   all  = Utilities::MPI::all_gather(comm, packed);
    unsigned int j    = 0;
    const auto   rank = Utilities::MPI::this_mpi_process(comm);
    for (unsigned int p = 0; p < all.size(); ++p)
      {
        if (p == rank)
          {
            j = end_own;
            continue;
          }
        for (std::size_t i = 0; i < all[p].size(); ++j)
          {
            State             &s = states[j];
            const unsigned int d = blocks[j].dofs.size();
            s.closed             = all[p][i] == 1.;
            s.compliant          = all[p][i] == 2.;
            s.open_diagonal      = all[p][i + 1];
            s.scale              = all[p][i + 2];
            s.b_norm2            = all[p][i + 3];
            s.b.assign(all[p].begin() + i + 4, all[p].begin() + i + 4 + d);
            i += 4 + d;
            s.frame.clear();
            s.foreign.assign(d, {});
            if (s.closed)
              {
                for (unsigned int l = 0; l < d; ++l, i += d)
                  s.frame.emplace_back(all[p].begin() + i,
                                       all[p].begin() + i + d);
                for (unsigned int l = 0; l < d; ++l)
                  {
                    const auto count = static_cast<unsigned int>(all[p][i++]);
                    for (unsigned int e = 0; e < count; ++e, i += 2)
                      s.foreign[l].emplace_back(
                        static_cast<unsigned int>(all[p][i]), all[p][i + 1]);
                  }
              }
          }
      }
  }

  void
  MultiplierCondensation::import_rows()
  {
    // The rows of the closed slave nodes of other processes whose
    // multipliers reach this process's rows (the fill of a master row).
    remote.reset();
    if (!parallel)
      return;
    std::set<int> needed;
    for (const auto row : owned_displacements)
      {
        int                    n      = 0;
        double                *values = nullptr;
        int                   *idx    = nullptr;
        const Epetra_BlockMap *cmap   = nullptr;
        row_view(row, n, values, idx, cmap);
        for (int e = 0; e < n; ++e)
          {
            const types::global_dof_index c = cmap->GID(idx[e]);
            if (c < n_u || values[e] == 0.)
              continue;
            const unsigned int j = c - n_u;
            if (states[j].closed && (j < first_own || j >= end_own))
              for (const auto d : blocks[j].dofs)
                needed.insert(static_cast<int>(d));
            // A compliant multiplier's row (C_j) for its fill.
            if (states[j].compliant && (j < first_own || j >= end_own))
              needed.insert(static_cast<int>(blocks[j].multiplier));
          }
      }
    const auto            &A = J->trilinos_matrix();
    const std::vector<int> rows(needed.begin(), needed.end());
    Epetra_Map             row_map(-1, rows.size(), rows.data(), 0, A.Comm());
    Epetra_Import          importer(row_map, A.RowMap());
    remote = std::make_unique<Epetra_CrsMatrix>(Copy, row_map, 0);
    // Epetra returns positive codes as warnings (storage grown for the
    // rows received): only a negative one is an error, and FillComplete
    // is collective, so every process calls it whatever its code.
    const int import = remote->Import(A, importer, Insert);
    const int fill   = remote->FillComplete(A.DomainMap(), A.RangeMap());
    throw_first_failure<std::runtime_error>(
      (import < 0 || fill < 0) ?
        "the elimination of the contact multipliers could not import "
        "the rows of other processes' slave nodes (Epetra error " +
          std::to_string(std::min(import, fill)) + ")" :
        std::string(),
      comm);
  }

  void
  MultiplierCondensation::condense(const TrilinosWrappers::SparseMatrix &J_in)
  {
    J = &J_in;
    remote.reset();
    // Collective: the first failure, as NotCondensable if any process's
    // was one (every process then takes the same way on).
    std::string failure;
    bool        not_condensable = false;
    const auto  fail_together   = [&]() {
      if (parallel)
        not_condensable =
          Utilities::MPI::max(not_condensable ? 1 : 0, comm) > 0;
      const std::string message =
        parallel ? first_failure_on_any_process(failure, comm) : failure;
      if (message.empty())
        return;
      J = nullptr;
      if (not_condensable)
        throw NotCondensable(message);
      throw std::runtime_error(message);
    };
    try
      {
        for (unsigned int j = first_own; j < end_own; ++j)
          compute_state(j);
      }
    catch (const NotCondensable &e)
      {
        failure         = e.what();
        not_condensable = true;
      }
    catch (const std::exception &e)
      {
        failure = e.what();
      }
    fail_together();
    if (parallel)
      share_states();
    // A hanging slave node's force in its parents' rows: known while it is
    // open; a closed one (its own rows empty) was refused above.
    for (unsigned int j = first_own; j < end_own && failure.empty(); ++j)
      for (const auto &entries : states[j].foreign)
        for (const auto &[k, value] : entries)
          if (states[k].closed || states[k].compliant)
            {
              failure         = "a slave node's rows hold the force of another "
                                "closed slave node";
              not_condensable = true;
            }
    fail_together();
    if (parallel)
      import_rows();

    condensed.reset(); // before its successor is built (peak memory)
    // Local work: an error here is thrown on every process before the
    // collective FillComplete.
    failure.clear();
    try
      {
        // Two passes over the rows: the number of distinct columns (Epetra's
        // static profile), then the values.
        const unsigned int n_rows = owned_displacements.n_elements();
        std::vector<int>   counts(n_rows, 0);
        std::vector<types::global_dof_index> stamp(n_u,
                                                   numbers::invalid_dof_index);
        unsigned int                         r = 0;
        for (const auto row : owned_displacements)
          {
            condensed_row(row,
                          [&](const types::global_dof_index c, const double) {
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
      }
    catch (const std::exception &e)
      {
        failure = e.what();
      }
    if (parallel)
      throw_first_failure<std::runtime_error>(failure, comm);
    else if (!failure.empty())
      throw std::runtime_error(failure);
    condensed->FillComplete(*map, *map);

    // What condense_rhs() and expand() need of J, so that J itself can be
    // released until the next Jacobian (LinearSolver::keeps_matrix()): the
    // multiplier entries of the rows of open nodes and master nodes, and
    // the displacement part of the rows of this process's closed nodes.
    // Under MPI also the entries of other processes those read: the
    // right-hand side at the nodes of the multipliers coupled here, and
    // the solution at the columns of the closed nodes' rows.
    std::vector<types::global_dof_index> columns;
    int                                  n      = 0;
    double                              *values = nullptr;
    std::vector<types::global_dof_index> rhs_reads, solution_reads;
    couplings.clear();
    for (const auto row : owned_displacements)
      {
        const int jb = block_of[row];
        if (jb >= 0 && states[jb].closed)
          continue;
        row_of_j(row, n, values, columns);
        for (int e = 0; e < n; ++e)
          if (columns[e] >= n_u && values[e] != 0.)
            {
              const unsigned int j = columns[e] - n_u;
              couplings.push_back({row, j, values[e]});
              if (states[j].closed)
                {
                  rhs_reads.insert(rhs_reads.end(),
                                   blocks[j].dofs.begin(),
                                   blocks[j].dofs.end());
                  for (const auto &entries : states[j].foreign)
                    for (const auto &entry : entries)
                      rhs_reads.push_back(blocks[entry.first].multiplier);
                }
              else
                rhs_reads.push_back(blocks[j].multiplier);
            }
      }
    // The solution entries expand() reads for column @p c: a closed
    // node's column is read in its frame, i.e. at all of the node's DoFs.
    const auto read_column = [&](const types::global_dof_index c) {
      const int jc = block_of[c];
      if (jc >= 0 && states[jc].closed)
        solution_reads.insert(solution_reads.end(),
                              blocks[jc].dofs.begin(),
                              blocks[jc].dofs.end());
      else
        solution_reads.push_back(c);
    };
    compliant_rows.assign(blocks.size(), {});
    for (unsigned int j = first_own; j < end_own; ++j)
      if (states[j].compliant)
        {
          row_of_j(blocks[j].multiplier, n, values, columns);
          for (int e = 0; e < n; ++e)
            if (columns[e] < n_u && values[e] != 0.)
              {
                compliant_rows[j].emplace_back(columns[e], values[e]);
                read_column(columns[e]);
              }
        }
    closed_rows.assign(blocks.size(), {});
    for (unsigned int j = first_own; j < end_own; ++j)
      if (states[j].closed)
        for (const auto &entries : states[j].foreign)
          for (const auto &entry : entries)
            rhs_reads.push_back(blocks[entry.first].multiplier);
    for (unsigned int j = first_own; j < end_own; ++j)
      if (states[j].closed)
        for (const auto d : blocks[j].dofs)
          {
            row_of_j(d, n, values, columns);
            std::vector<std::pair<types::global_dof_index, double>> entries;
            for (int e = 0; e < n; ++e)
              if (columns[e] < n_u)
                {
                  entries.emplace_back(columns[e], values[e]);
                  read_column(columns[e]);
                }
            closed_rows[j].push_back(std::move(entries));
          }
    const auto ghosts_of = [](std::vector<types::global_dof_index> &reads,
                              const IndexSet                       &own,
                              const types::global_dof_index         size) {
      std::sort(reads.begin(), reads.end());
      reads.erase(std::unique(reads.begin(), reads.end()), reads.end());
      IndexSet ghosts(size);
      for (const auto i : reads)
        if (!own.is_element(i))
          ghosts.add_index(i);
      ghosts.compress();
      return ghosts;
    };
    rhs_ghosts      = ghosts_of(rhs_reads, owned, owned.size());
    solution_ghosts = ghosts_of(solution_reads, owned_displacements, n_u);
    remote.reset();
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
              // Q^T u_S: the mode's component along direction k (the
              // node's DoFs are owned here with the row).
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
    const TrilinosWrappers::MPI::Vector &b_in,
    TrilinosWrappers::MPI::Vector       &condensed_b) const
  {
    // Under MPI b at the nodes of the multipliers coupled to this
    // process's rows, imported.
    TrilinosWrappers::MPI::Vector ghosted;
    if (parallel)
      {
        ghosted.reinit(b_in.locally_owned_elements(), rhs_ghosts, comm);
        ghosted = b_in;
      }
    const TrilinosWrappers::MPI::Vector &b = parallel ? ghosted : b_in;
    // The values are summed here and inserted once: a vector written by
    // insertion on some processes and by addition on others is assembled
    // differently by each (Epetra_FEVector::GlobalAssemble), and the
    // processes then wait for each other forever.
    std::vector<double> value(owned_displacements.n_elements(), 0.);
    const auto at = [&](const types::global_dof_index row) -> double & {
      return value[owned_displacements.index_within_set(row)];
    };
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
                v += s.frame[l][k] *
                     (b(blocks[jb].dofs[l]) - foreign_force(jb, l, b));
          }
        else
          v = b(row);
        at(row) = v;
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
              bf += s.b[l] * (b(block.dofs[l]) - foreign_force(c.block, l, b));
            at(c.row) -= c.value * bf / s.b_norm2;
          }
        else
          at(c.row) -= c.value * b(block.multiplier) / s.open_diagonal;
      }
    condensed_b.reinit(owned_displacements, comm);
    for (const auto row : owned_displacements)
      condensed_b(row) = at(row);
    condensed_b.compress(VectorOperation::insert);
  }

  double
  MultiplierCondensation::foreign_force(
    const unsigned int                   j,
    const unsigned int                   l,
    const TrilinosWrappers::MPI::Vector &b) const
  {
    double f = 0.;
    for (const auto &[k, value] : states[j].foreign[l])
      f += value * b(blocks[k].multiplier) / states[k].open_diagonal;
    return f;
  }

  void
  MultiplierCondensation::expand(const TrilinosWrappers::MPI::Vector &b_in,
                                 const TrilinosWrappers::MPI::Vector &xc_in,
                                 TrilinosWrappers::MPI::Vector       &x) const
  {
    // Under MPI the condensed solution at the columns of this process's
    // closed nodes' rows, imported.
    TrilinosWrappers::MPI::Vector ghosted;
    if (parallel)
      {
        ghosted.reinit(owned_displacements, solution_ghosts, comm);
        ghosted = xc_in;
      }
    const TrilinosWrappers::MPI::Vector &xc = parallel ? ghosted : xc_in;
    // And the right-hand side at the open multipliers of hanging nodes on
    // other processes (foreign_force()).
    TrilinosWrappers::MPI::Vector ghosted_b;
    if (parallel)
      {
        ghosted_b.reinit(b_in.locally_owned_elements(), rhs_ghosts, comm);
        ghosted_b = b_in;
      }
    const TrilinosWrappers::MPI::Vector &b = parallel ? ghosted_b : b_in;
    // du: the condensed unknowns, closed nodes rotated back (du_S = Q x_S).
    std::vector<double> du(n_u, 0.);
    const auto          rotate_back = [&](const types::global_dof_index row) {
      const int jb = block_of[row];
      if (jb >= 0 && states[jb].closed)
        {
          const auto &block = blocks[jb];
          double      v     = 0.;
          for (unsigned int k = 0; k < block.dofs.size(); ++k)
            v += states[jb].frame[component_of[row]][k] * xc(block.dofs[k]);
          du[row] = v;
        }
      else
        du[row] = xc(row);
    };
    for (const auto row : owned_displacements)
      rotate_back(row);
    for (const auto row : solution_ghosts)
      rotate_back(row);
    for (const auto row : owned_displacements)
      x(row) = du[row];
    for (unsigned int j = first_own; j < end_own; ++j)
      {
        const auto &s     = states[j];
        const auto &block = blocks[j];
        if (s.compliant)
          {
            // dl_j = (h_j - C_j du) / E_jj.
            double r = b(block.multiplier);
            for (const auto &[column, value] : compliant_rows[j])
              r -= value * du[column];
            x(block.multiplier) = r / s.open_diagonal;
            continue;
          }
        if (!s.closed)
          {
            x(block.multiplier) = b(block.multiplier) / s.open_diagonal;
            continue;
          }
        // dl_j = b_j^T (f_S - A_S du - B_Sh dl_h) / |b_j|^2 (h: open
        // hanging nodes constrained to this one).
        double v = 0.;
        for (unsigned int l = 0; l < block.dofs.size(); ++l)
          {
            double r = b(block.dofs[l]) - foreign_force(j, l, b);
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
    for (unsigned int j = first_own; j < end_own; ++j)
      n += states[j].closed ? 1 : 0;
    return parallel ? Utilities::MPI::sum(n, comm) : n;
  }
} // namespace glide
