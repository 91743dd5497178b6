#include <glide/contact/contact.h>
#include <glide/output/statistics.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>

#include <fstream>
#include <sstream>

namespace glide
{
  using namespace dealii;

  template <int dim>
  Contact<dim>::Contact(const Scene           &scene,
                        const Elasticity<dim> &elasticity,
                        MPI_Comm               comm)
    : scene(scene)
    , elasticity(elasticity)
    , comm(comm)
  {}

  template <int dim>
  void
  Contact<dim>::setup(const types::global_dof_index first_multiplier)
  {
    for (const auto &b : scene.bodies)
      max_youngs_modulus =
        std::max(max_youngs_modulus, b.material.youngs_modulus);
    const auto &dof_handler  = elasticity.get_dof_handler();
    const auto &fe           = dof_handler.get_fe();
    const auto &mapping      = elasticity.get_mapping();
    const auto &owned        = elasticity.displacement_owned();
    const bool  axisymmetric = scene.analysis == AnalysisType::axisymmetric;
    const auto &unit_points  = fe.get_unit_support_points();

    const QGauss<dim - 1>                quadrature(scene.degree + 1);
    FEFaceValues<dim>                    face_values(mapping,
                                  fe,
                                  quadrature,
                                  update_values | update_JxW_values |
                                    update_quadrature_points);
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());

    for (const auto &p : scene.contact_pairs)
      {
        const std::string path = "Contact pair " + p.name;
        Pair              pair;
        pair.parameters = &p;
        pair.master     = std::make_unique<RigidMaster<dim>>(p, path);

        std::set<types::boundary_id> ids;
        for (const auto &name : Utilities::split_string_list(p.slave, ','))
          for (const auto id :
               elasticity.get_mesh().surface(name, path + "/Slave"))
            ids.insert(id);

        // Slave nodes: every node of a slave face, keyed by its x DoF, with
        // the tributary area int N_a dA (times 2 pi r in axisymmetric
        // analysis) and the mean size of the adjacent slave facets. Ghost
        // cells contribute too, so that nodes on a process boundary get
        // their whole area.
        std::map<types::global_dof_index, SlaveNode>    found;
        std::map<types::global_dof_index, unsigned int> n_facets;
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            if (cell->is_artificial())
              continue;
            for (const auto f : cell->face_indices())
              {
                if (!cell->face(f)->at_boundary() ||
                    ids.count(cell->face(f)->boundary_id()) == 0)
                  continue;
                cell->get_dof_indices(cell_dofs);
                face_values.reinit(cell, f);
                // Nodes of this face: base index -> cell DoFs per component.
                std::map<unsigned int, std::array<unsigned int, dim>> nodes;
                for (unsigned int i = 0; i < fe.n_dofs_per_face(f); ++i)
                  {
                    const unsigned int k =
                      fe.face_to_cell_index(i,
                                            f,
                                            cell->face_orientation(f),
                                            cell->face_flip(f),
                                            cell->face_rotation(f));
                    const auto ci = fe.system_to_component_index(k);
                    nodes[ci.second][ci.first] = k;
                  }
                for (const auto &[base, k] : nodes)
                  {
                    SlaveNode &node = found[cell_dofs[k[0]]];
                    for (unsigned int c = 0; c < dim; ++c)
                      node.dofs[c] = cell_dofs[k[c]];
                    node.X =
                      mapping.transform_unit_to_real_cell(cell,
                                                          unit_points[k[0]]);
                    for (unsigned int q = 0; q < quadrature.size(); ++q)
                      node.area +=
                        face_values.shape_value(k[0], q) * face_values.JxW(q) *
                        (axisymmetric ? 2 * numbers::PI *
                                          face_values.quadrature_point(q)[0] :
                                        1.);
                    node.size += cell->face(f)->diameter();
                    ++n_facets[cell_dofs[k[0]]];
                  }
              }
          }
        for (auto &[dof, node] : found)
          if (owned.is_element(dof))
            {
              node.size /= n_facets[dof];
              node.c = max_youngs_modulus * node.area / node.size;
              const double stiffness = p.penalty_stiffness > 0 ?
                                         p.penalty_stiffness :
                                         1000. * max_youngs_modulus / node.size;
              node.k                 = stiffness * node.area;
              pair.nodes.push_back(node);
            }
        const unsigned int n_global =
          Utilities::MPI::sum(static_cast<unsigned int>(pair.nodes.size()),
                              comm);
        require(n_global > 0,
                "Contact pair '" + p.name + "': the slave surface '" + p.slave +
                  "' has no nodes.");
        pairs.push_back(std::move(pair));
      }

    // Number the multipliers of hard pairs: this process's block follows
    // those of the lower ranks.
    types::global_dof_index n_local = 0;
    for (const auto &pair : pairs)
      if (pair.parameters->enforcement == Enforcement::hard)
        n_local += pair.nodes.size();
    types::global_dof_index offset = 0;
    MPI_Exscan(&n_local, &offset, 1, DEAL_II_DOF_INDEX_MPI_TYPE, MPI_SUM, comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      offset = 0;
    total_multipliers = Utilities::MPI::sum(n_local, comm);
    multipliers       = IndexSet(first_multiplier + total_multipliers);
    multipliers.add_range(first_multiplier + offset,
                          first_multiplier + offset + n_local);
    types::global_dof_index next = first_multiplier + offset;
    for (auto &pair : pairs)
      if (pair.parameters->enforcement == Enforcement::hard)
        for (auto &node : pair.nodes)
          node.multiplier = next++;
  }

  template <int dim>
  void
  Contact<dim>::add_sparsity(DynamicSparsityPattern &dsp) const
  {
    for (const auto &pair : pairs)
      for (const auto &node : pair.nodes)
        {
          std::vector<types::global_dof_index> idx(node.dofs.begin(),
                                                   node.dofs.end());
          if (node.multiplier != numbers::invalid_dof_index)
            idx.push_back(node.multiplier);
          // Through the constraints: a slave node at a hanging node couples
          // with the DoFs it is constrained to.
          elasticity.update_constraints().add_entries_local_to_global(idx,
                                                                      dsp,
                                                                      false);
        }
  }

  template <int dim>
  void
  Contact<dim>::set_time(const double t)
  {
    for (auto &pair : pairs)
      pair.master->set_time(t);
  }

  template <int dim>
  typename Contact<dim>::NodeState
  Contact<dim>::state(const Pair       &pair,
                      const SlaveNode  &node,
                      const VectorType &U) const
  {
    NodeState s;
    s.x = node.X;
    for (unsigned int d = 0; d < dim; ++d)
      s.x[d] += U[node.dofs[d]];
    s.projection   = pair.master->project(s.x);
    const double g = s.projection.gap;
    if (node.multiplier != numbers::invalid_dof_index)
      {
        s.lambda = U[node.multiplier];
        // Active where lambda - c g >= 0: then C = c g (closed, g -> 0);
        // otherwise C = lambda (open, lambda -> 0).
        s.closed = s.lambda - node.c * g >= 0.;
      }
    else
      {
        s.lambda = node.k * std::max(0., -g);
        s.closed = g < 0.;
      }
    return s;
  }

  template <int dim>
  void
  Contact<dim>::assemble(const VectorType &U,
                         VectorType       *F,
                         MatrixType       *J) const
  {
    const auto &constraints = elasticity.update_constraints();
    for (const auto &pair : pairs)
      {
        const bool hard = pair.parameters->enforcement == Enforcement::hard;
        const unsigned int                   n = dim + (hard ? 1 : 0);
        Vector<double>                       rhs(n);
        FullMatrix<double>                   K(n, n);
        std::vector<types::global_dof_index> idx(n);
        for (const auto &node : pair.nodes)
          {
            const NodeState s   = state(pair, node, U);
            const auto     &nrm = s.projection.normal;
            const auto     &H   = s.projection.curvature;
            const double    g   = s.projection.gap;
            rhs                 = 0;
            K                   = 0;
            for (unsigned int d = 0; d < dim; ++d)
              idx[d] = node.dofs[d];
            // Displacement rows: -lambda dg/du, with lambda the contact force.
            for (unsigned int d = 0; d < dim; ++d)
              {
                rhs(d) = -s.lambda * nrm[d];
                for (unsigned int e = 0; e < dim; ++e)
                  K(d, e) = -s.lambda * H[d][e];
              }
            if (hard)
              {
                idx[dim] = node.multiplier;
                rhs(dim) = s.closed ? node.c * g : s.lambda;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    K(d, dim) = -nrm[d];
                    K(dim, d) = s.closed ? node.c * nrm[d] : 0.;
                  }
                K(dim, dim) = s.closed ? 0. : 1.;
              }
            else if (s.closed)
              for (unsigned int d = 0; d < dim; ++d)
                for (unsigned int e = 0; e < dim; ++e)
                  K(d, e) += node.k * nrm[d] * nrm[e];
            if (F && J)
              constraints.distribute_local_to_global(K, rhs, idx, *J, *F);
            else if (F)
              constraints.distribute_local_to_global(rhs, idx, *F);
            else if (J)
              constraints.distribute_local_to_global(K, idx, *J);
          }
      }
    if (F)
      F->compress(VectorOperation::add);
    if (J)
      J->compress(VectorOperation::add);
  }

  template <int dim>
  void
  Contact<dim>::set_scaling(VectorType  &residual_scale,
                            VectorType  &solution_scale,
                            const double scale) const
  {
    for (const auto i : multipliers)
      {
        residual_scale[i] = scale;
        solution_scale[i] = scale;
      }
    residual_scale.compress(VectorOperation::insert);
    solution_scale.compress(VectorOperation::insert);
  }

  template <int dim>
  std::vector<std::pair<std::string, std::string>>
  Contact<dim>::statistics(const VectorType &U) const
  {
    std::vector<std::pair<std::string, std::string>> row;
    const char                                      *axis[] = {"x", "y", "z"};
    for (const auto &pair : pairs)
      {
        unsigned int   active       = 0;
        double         normal_force = 0, penetration = 0;
        Tensor<1, dim> force;
        for (const auto &node : pair.nodes)
          {
            const NodeState s = state(pair, node, U);
            active += s.closed ? 1 : 0;
            normal_force += s.lambda;
            force += s.lambda * s.projection.normal;
            penetration = std::max(penetration, -s.projection.gap);
          }
        const std::string p = "contact_" + pair.parameters->name + "_";
        row.emplace_back(p + "active",
                         std::to_string(Utilities::MPI::sum(active, comm)));
        row.emplace_back(p + "normal_force",
                         format_number(
                           Utilities::MPI::sum(normal_force, comm)));
        force = Utilities::MPI::sum(force, comm);
        for (unsigned int d = 0; d < dim; ++d)
          row.emplace_back(p + "force_" + axis[d], format_number(force[d]));
        row.emplace_back(p + "max_penetration",
                         format_number(Utilities::MPI::max(penetration, comm)));
      }
    return row;
  }

  template <int dim>
  void
  Contact<dim>::write_nodes(const VectorType  &U,
                            const std::string &directory,
                            const unsigned int step) const
  {
    for (const auto &pair : pairs)
      {
        std::ostringstream rows;
        rows.precision(12);
        for (const auto &node : pair.nodes)
          {
            const NodeState s = state(pair, node, U);
            for (unsigned int d = 0; d < dim; ++d)
              rows << node.X[d] << ",";
            for (unsigned int d = 0; d < dim; ++d)
              rows << s.x[d] << ",";
            rows << s.projection.gap << "," << s.lambda << ","
                 << s.lambda / node.area << "," << (s.closed ? 1 : 0) << "\n";
          }
        const auto all = Utilities::MPI::gather(comm, rows.str(), 0);
        if (Utilities::MPI::this_mpi_process(comm) != 0)
          continue;
        char number[16];
        std::snprintf(number, sizeof(number), "%04u", step);
        const std::string file = directory + "/contact-" +
                                 pair.parameters->name + "-" + number + ".csv";
        std::ofstream out(file + ".tmp");
        const char   *X[] = {"X", "Y", "Z"}, *x[] = {"x", "y", "z"};
        for (unsigned int d = 0; d < dim; ++d)
          out << X[d] << ",";
        for (unsigned int d = 0; d < dim; ++d)
          out << x[d] << ",";
        out << "COPEN,force,CPRESS,CSTATUS\n";
        for (const auto &r : all)
          out << r;
        out.close();
        std::rename((file + ".tmp").c_str(), file.c_str());
      }
  }

  template <int dim>
  std::vector<std::string>
  Contact<dim>::active_effects() const
  {
    std::vector<std::string> e;
    for (const auto &pair : pairs)
      {
        const auto &p = *pair.parameters;
        e.push_back("contact pair " + p.name +
                    " (node to surface, finite sliding, " + p.master + ", " +
                    (p.enforcement == Enforcement::hard ? "hard" : "penalty") +
                    ", " +
                    std::to_string(Utilities::MPI::sum(
                      static_cast<unsigned int>(pair.nodes.size()), comm)) +
                    " slave nodes)");
      }
    return e;
  }

  template class Contact<2>;
  template class Contact<3>;
} // namespace glide
