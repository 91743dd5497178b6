#include <glide/base/collective_failure.h>
#include <glide/contact/contact.h>
#include <glide/contact/small_sliding_formulation.h>
#include <glide/output/statistics.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

namespace glide
{
  using namespace dealii;

  template <int dim>
  std::array<Tensor<1, dim>, dim - 1>
  contact_tangents(const Tensor<1, dim> &n)
  {
    std::array<Tensor<1, dim>, dim - 1> t;
    if constexpr (dim == 2)
      {
        t[0][0] = -n[1];
        t[0][1] = n[0];
      }
    else
      {
        // The global x axis projected onto the tangent plane; the z axis if
        // x is within 0.1 degrees of the normal.
        Tensor<1, dim> e;
        e[0] = 1.;
        if (std::abs(n[0]) > std::cos(0.1 * numbers::PI / 180.))
          {
            e[0] = 0.;
            e[2] = 1.;
          }
        t[0]           = e - (e * n) * n;
        const double l = t[0].norm();
        if (l > 0)
          t[0] /= l;
        t[1] = cross_product_3d(n, t[0]);
      }
    return t;
  }

  template std::array<Tensor<1, 2>, 1>
  contact_tangents<2>(const Tensor<1, 2> &);
  template std::array<Tensor<1, 3>, 2>
  contact_tangents<3>(const Tensor<1, 3> &);

  namespace
  {
    /**
     * Sum the slave nodes' partial quantities (from this process's own
     * cells, hanging nodes condensed) at the processes that own the nodes:
     * each process sends what it holds of a node it does not own to the
     * node's owner. The owners then hold the whole tributary area,
     * normal, surface mass, facet sizes and merged hanging nodes; the
     * other entries stay partial (only owned nodes are constraint points).
     */
    template <int dim>
    void
    sum_at_owners(std::map<types::global_dof_index, SlaveNode<dim>> &found,
                  std::map<types::global_dof_index, unsigned int>   &n_facets,
                  const IndexSet                                    &owned,
                  MPI_Comm                                           comm)
    {
      IndexSet others(owned.size());
      for (const auto &[key, node] : found)
        if (!owned.is_element(key) &&
            (n_facets[key] > 0 || node.measure != 0. || !node.hanging.empty()))
          others.add_index(key);
      others.compress();
      const std::vector<unsigned int> owner =
        Utilities::MPI::compute_index_owner(owned, others, comm);
      std::map<unsigned int, std::vector<double>> send;
      unsigned int                                n = 0;
      for (const auto key : others)
        {
          const auto &node = found.at(key);
          auto       &data = send[owner[n++]];
          data.push_back(static_cast<double>(key));
          for (unsigned int d = 0; d < dim; ++d)
            data.push_back(static_cast<double>(node.dofs[d]));
          for (unsigned int d = 0; d < dim; ++d)
            data.push_back(node.X[d]);
          for (unsigned int d = 0; d < dim; ++d)
            data.push_back(node.normal[d]);
          data.push_back(node.area);
          data.push_back(node.measure);
          data.push_back(node.size);
          data.push_back(n_facets[key]);
          data.push_back(node.mass.size());
          for (const auto &[b, m] : node.mass)
            {
              data.push_back(static_cast<double>(b));
              data.push_back(m);
            }
          data.push_back(node.hanging.size());
          for (const auto &[h, w] : node.hanging)
            {
              data.push_back(static_cast<double>(h));
              data.push_back(w);
            }
        }
      const auto index = [](const double x) {
        return static_cast<types::global_dof_index>(x);
      };
      for (const auto &[rank, data] : Utilities::MPI::some_to_some(comm, send))
        for (std::size_t i = 0; i < data.size();)
          {
            const auto key  = index(data[i++]);
            auto      &node = found[key];
            for (unsigned int d = 0; d < dim; ++d)
              node.dofs[d] = index(data[i++]);
            for (unsigned int d = 0; d < dim; ++d)
              node.X[d] = data[i++];
            for (unsigned int d = 0; d < dim; ++d)
              node.normal[d] += data[i++];
            node.area += data[i++];
            node.measure += data[i++];
            node.size += data[i++];
            n_facets[key] += static_cast<unsigned int>(data[i++]);
            const auto n_mass = static_cast<std::size_t>(data[i++]);
            for (std::size_t j = 0; j < n_mass; ++j, i += 2)
              node.mass[index(data[i])] += data[i + 1];
            const auto n_hanging = static_cast<std::size_t>(data[i++]);
            for (std::size_t j = 0; j < n_hanging; ++j, i += 2)
              {
                const auto h = index(data[i]);
                if (std::none_of(node.hanging.begin(),
                                 node.hanging.end(),
                                 [&](const auto &e) { return e.first == h; }))
                  node.hanging.emplace_back(h, data[i + 1]);
              }
          }
    }
  } // namespace

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
  Contact<dim>::condense_hanging_nodes(
    std::map<types::global_dof_index, SlaveNode<dim>> &found,
    std::map<types::global_dof_index, unsigned int>   &n_facets) const
  {
    // A slave node at a hanging node of a locally refined slave surface
    // (3D) has no displacement of its own: u_h = sum_p w_p u_p over the
    // nodes of the coarse face's edge (or face) it lies on, all of them
    // slave nodes too. As a constraint point of its own it adds a row that
    // its parents' rows nearly repeat: on a flat master, with h and its
    // parents closed, the gap at h is the mean of theirs, and the Newton
    // system is singular. Seen on hertz-3d.prm with 27 times the load (the
    // contact zone then crosses the refinement's border): full Newton
    // steps raised the scaled residual from 6e-3 to 358, and the run ended
    // after 6 cut-backs; with the border outside the contact zone the same
    // load converges in 7, 5, 4, 4 iterations. Quadratic elements add the
    // extreme case: the fine faces' vertex at a coarse edge's midpoint is
    // constrained to equal the coarse node there (x_h = 1.0 x_p), two
    // identical rows (hertz-3d-elastic.prm with degree 2 took 8 cut-backs).
    // So the constraint points are the slave nodes with displacements of
    // their own, as in deal.II's step-42, and each hanging node's
    // tributary area, area-weighted normal and surface mass go to its
    // parents with the constraint's weights: the areas are then int N_p^c
    // dA of the constrained shape functions N_p^c = N_p + sum_h w_hp N_h,
    // so a uniform pressure still gives the exact nodal forces. Mortar
    // adds the hanging node's weighted gap, weight and master terms to its
    // parents' with the same weights (SlaveNode::hanging): its multiplier
    // space is that of the constrained shape functions. 2D has no hanging
    // node on a boundary. The hanging-node constraints alone decide (the Newton
    // system's, which add the boundary conditions, are built after the
    // contact pairs).
    const auto &dof_handler = elasticity.get_dof_handler();
    IndexSet    relevant;
    DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
    AffineConstraints<double> constraints(relevant);
    DoFTools::make_hanging_node_constraints(dof_handler, constraints);
    constraints.close();
    std::map<types::global_dof_index, types::global_dof_index> node_of_dof;
    for (const auto &[key, node] : found)
      for (const auto d : node.dofs)
        node_of_dof[d] = key;
    // Hanging node -> (parent, weight), the same for every component.
    std::map<types::global_dof_index,
             std::vector<std::pair<types::global_dof_index, double>>>
      parents_of;
    for (const auto &[key, node] : found)
      {
        std::vector<std::pair<types::global_dof_index, double>> parents;
        bool                                                    ok = true;
        for (unsigned int c = 0; c < dim && ok; ++c)
          {
            const auto *entries =
              constraints.get_constraint_entries(node.dofs[c]);
            ok = entries != nullptr && !entries->empty() &&
                 constraints.get_inhomogeneity(node.dofs[c]) == 0.;
            std::vector<std::pair<types::global_dof_index, double>> these;
            for (unsigned int e = 0; ok && e < entries->size(); ++e)
              {
                const auto [d, w] = (*entries)[e];
                const auto it     = node_of_dof.find(d);
                ok = it != node_of_dof.end() && it->second != key &&
                     found.at(it->second).dofs[c] == d;
                if (ok)
                  these.emplace_back(it->second, w);
              }
            if (!ok)
              break;
            std::sort(these.begin(), these.end());
            ok      = c == 0 || these == parents;
            parents = std::move(these);
          }
        if (ok)
          parents_of[key] = std::move(parents);
      }
    // The surface mass int N_a N_b dA becomes C^T M C: columns first (every
    // node's entries at a hanging node go to its parents), then rows.
    for (auto &[key, node] : found)
      {
        std::vector<std::pair<types::global_dof_index, double>> moved;
        for (auto it = node.mass.begin(); it != node.mass.end();)
          if (parents_of.count(it->first) > 0)
            {
              moved.emplace_back(*it);
              it = node.mass.erase(it);
            }
          else
            ++it;
        for (const auto &[hanging, m] : moved)
          for (const auto &[p, w] : parents_of.at(hanging))
            node.mass[p] += w * m;
      }
    for (const auto &[hanging, parents] : parents_of)
      {
        const auto &from = found.at(hanging);
        for (const auto &[p, w] : parents)
          {
            auto &into = found.at(p);
            into.area += w * from.area;
            into.measure += std::abs(w) * from.measure;
            into.normal += w * from.normal;
            into.hanging.emplace_back(hanging, w);
            for (const auto &[b, m] : from.mass)
              into.mass[b] += w * m;
            // One point (identity): the facets of both count for its size.
            if (parents.size() == 1)
              {
                into.size += from.size;
                n_facets[p] += n_facets[hanging];
              }
          }
      }
    for (const auto &[hanging, parents] : parents_of)
      {
        found.erase(hanging);
        n_facets.erase(hanging);
      }
  }

  template <int dim>
  std::vector<SlaveNode<dim>>
  Contact<dim>::find_slave_nodes(const ContactPairParameters &p,
                                 const std::string           &path,
                                 bool                        &node_based,
                                 double &slave_modulus) const
  {
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
                                    update_quadrature_points |
                                    update_normal_vectors);
    std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
    slave_modulus = std::numeric_limits<double>::infinity();
    std::map<types::global_dof_index, SlaveNode<dim>> found;
    std::map<types::global_dof_index, unsigned int>   n_facets;
    node_based = std::any_of(scene.node_sets.begin(),
                             scene.node_sets.end(),
                             [&](const auto &n) { return n.name == p.slave; });
    if (node_based)
      {
        // Node-based slave surface (as Abaqus' *SURFACE, TYPE=NODE):
        // the vertices of the node set, each with contact area 1 (so
        // CPRESS is the nodal force) and, as its size, the mean
        // diameter of the cells around it.
        for (const auto &[dofs, X] :
             elasticity.find_nodes(p.slave, path + "/Slave", false))
          {
            SlaveNode<dim> &node = found[dofs[0]];
            node.dofs            = dofs;
            node.X               = X;
            node.area            = 1.;
          }
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (!cell->is_artificial())
            for (const auto v : cell->vertex_indices())
              {
                const auto it = found.find(cell->vertex_dof_index(v, 0));
                if (it == found.end())
                  continue;
                slave_modulus = std::min(slave_modulus,
                                         elasticity.youngs_modulus_of_body(
                                           cell->material_id()));
                it->second.size += cell->diameter();
                ++n_facets[it->first];
              }
      }
    else
      {
        std::set<types::boundary_id> ids;
        for (const auto &name : Utilities::split_string_list(p.slave, ','))
          for (const auto id :
               elasticity.get_mesh().surface(name, path + "/Slave"))
            ids.insert(id);

        // Slave nodes: every node of a slave face, keyed by its x DoF, with
        // the tributary area int N_a dA (times 2 pi r in axisymmetric
        // analysis) and the mean size of the adjacent slave facets. Each
        // process integrates over its own cells and the sums are gathered
        // at the nodes' owners (sum_at_owners()). Ghost cells only name
        // their nodes, for the hanging-node condensation: adding their
        // faces instead gave whole areas to nodes on a process boundary,
        // but not to a slave node whose hanging neighbour (a locally
        // refined 3D slave) has faces beyond the ghost layer: its CPRESS,
        // and with penalty its stiffness and the answer, depended on the
        // number of processes (4 % on a 3D patch test with 2).
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
                slave_modulus = std::min(slave_modulus,
                                         elasticity.youngs_modulus_of_body(
                                           cell->material_id()));
                // Nodes of this face: base index -> cell DoFs per
                // component.
                const auto nodes = face_node_indices<dim>(fe, cell, f);
                for (const auto &[base, k] : nodes)
                  {
                    SlaveNode<dim> &node = found[cell_dofs[k[0]]];
                    for (unsigned int c = 0; c < dim; ++c)
                      node.dofs[c] = cell_dofs[k[c]];
                    node.X =
                      mapping.transform_unit_to_real_cell(cell,
                                                          unit_points[k[0]]);
                    if (!cell->is_locally_owned())
                      continue;
                    for (unsigned int q = 0; q < quadrature.size(); ++q)
                      {
                        const double dA =
                          face_values.JxW(q) *
                          (axisymmetric ? 2 * numbers::PI *
                                            face_values.quadrature_point(q)[0] :
                                          1.);
                        node.area += face_values.shape_value(k[0], q) * dA;
                        node.measure +=
                          std::abs(face_values.shape_value(k[0], q)) * dA;
                      }
                    node.size += cell->face(f)->diameter();
                    ++n_facets[cell_dofs[k[0]]];
                    // For surface to surface: the area-weighted normal
                    // and the surface mass int N_a N_b dA of the
                    // node's neighbours on the slave surface.
                    for (unsigned int q = 0; q < quadrature.size(); ++q)
                      {
                        const double dA =
                          face_values.JxW(q) *
                          (axisymmetric ? 2 * numbers::PI *
                                            face_values.quadrature_point(q)[0] :
                                          1.);
                        node.normal += face_values.shape_value(k[0], q) * dA *
                                       face_values.normal_vector(q);
                        for (const auto &[other, l] : nodes)
                          node.mass[cell_dofs[l[0]]] +=
                            face_values.shape_value(k[0], q) *
                            face_values.shape_value(l[0], q) * dA;
                      }
                  }
              }
          }
      }
    slave_modulus = Utilities::MPI::min(slave_modulus, comm);
    if (!node_based)
      {
        condense_hanging_nodes(found, n_facets);
        if (Utilities::MPI::n_mpi_processes(comm) > 1)
          sum_at_owners(found, n_facets, owned, comm);
      }
    // A node without tributary area (the corner node on the axis of a
    // quadratic axisymmetric facet: int N r dr = 0 on a straight facet, a
    // few 1e-3 of int |N| r dr on a curved one) carries no share of any
    // pressure worth the name, and is no constraint point (as a hanging
    // node): its NCP constant c = E_pair A / h was round-off, so were its
    // open/closed decisions, and its surface-to-surface averaging region
    // (int N_i N_k dA / int N_i dA) divided by zero; the node switched in
    // every iteration and steps were cut back. Mortar keeps it: its dual
    // basis is built on all nodes of the slave facets.
    if (!node_based && p.formulation != "mortar")
      {
        for (auto it = found.begin(); it != found.end();)
          if (it->second.without_area())
            {
              n_facets.erase(it->first);
              it = found.erase(it);
            }
          else
            ++it;
      }
    std::vector<SlaveNode<dim>> nodes;
    for (auto &[dof, node] : found)
      if (owned.is_element(dof))
        {
          node.size /= n_facets[dof];
          nodes.push_back(node);
        }
    return nodes;
  }

  template <int dim>
  void
  Contact<dim>::setup(const types::global_dof_index first_multiplier)
  {
    max_youngs_modulus = elasticity.youngs_modulus_scale();
    pairs.clear();
    pairs.reserve(scene.contact_pairs.size());
    for (const auto &p : scene.contact_pairs)
      {
        const std::string path = "Contact pair " + p.name;
        Pair              pair;
        pair.parameters = &p;
        std::unique_ptr<RigidMaster<dim>>   master;
        std::unique_ptr<MasterSurface<dim>> surface;
        if (p.master_type == MasterType::surface)
          {
            std::set<types::boundary_id> master_ids;
            for (const auto &name : Utilities::split_string_list(p.master, ','))
              for (const auto id :
                   elasticity.get_mesh().surface(name, path + "/Master"))
                master_ids.insert(id);
            surface = std::make_unique<MasterSurface<dim>>(
              elasticity,
              master_ids,
              p.smoothing,
              path,
              Utilities::MPI::n_mpi_processes(comm) > 1);
            require(surface->n_facets_global() > 0,
                    "Contact pair '" + p.name + "': the master surface '" +
                      p.master + "' has no faces.");
          }
        else
          {
            master = std::make_unique<RigidMaster<dim>>(p, path);
            // Axisymmetric: a rigid circle is the section of a sphere
            // (centre on the axis) or of a torus, which lies wholly at
            // r >= 0. One that crosses the axis off its centre is neither:
            // its normal at the axis has a radial part that no surface of
            // revolution has (until 2026-12-07 accepted: a circle centred
            // at r = -0.3 put a radial force on the axis node, exit 0).
            // Checked along the whole motion, at 1001 load factors 0,
            // 0.001, ..., 1 (a cut-back may stop at any; until 2026-12-07
            // at 0, the first step's and 1 only), where the motion puts
            // the centre (a constant 'Translation' moves it at t = 0 too).
            if (dim == 2 && p.master_type == MasterType::rigid_circle &&
                scene.analysis == AnalysisType::axisymmetric)
              for (unsigned int k = 0; k <= 1000; ++k)
                {
                  const double t         = k / 1000.;
                  const double r         = master->centre_at(t)[0],
                               tolerance = 1e-10 * p.radius;
                  if (std::abs(r) <= tolerance || r >= p.radius - tolerance)
                    continue;
                  std::ostringstream text;
                  text << "Parameter '" << path
                       << "/Rigid master': in an axisymmetric scene a rigid "
                          "circle is the section of a sphere (its centre on "
                          "the axis, x = r = 0) or of a torus (wholly at "
                          "r >= 0: its centre at r >= 'Radius'); at load "
                          "factor "
                       << t << " its centre is at r = " << r
                       << " with 'Radius' = " << p.radius
                       << ", so it does not lie wholly at r >= 0. Check "
                          "'Point' (x = r of the centre), 'Radius', "
                          "'Translation' and 'Rotation'.";
                  throw InputError(text.str());
                }
          }

        for (const auto &name : Utilities::split_string_list(p.slave, ','))
          for (const auto &body : scene.bodies)
            require(!body.rigid || name.rfind(body.name + ".", 0) != 0,
                    "Contact pair '" + p.name + "': the slave surface '" +
                      name + "' belongs to the rigid body '" + body.name +
                      "'; a rigid body can only be the master (swap Slave "
                      "and Master).");
        // The contact modulus E_pair: the softer of the two sides sets
        // the contact stiffness, and so the scale of c, of the penalty
        // stiffness and of the contact rows (with E_max instead, a soft
        // body pressed by a body 1e6 times stiffer got c 1e6 times its
        // own stiffness, and its open/closed decisions followed the gap
        // alone).
        double master_modulus = std::numeric_limits<double>::infinity();
        if (p.master_type == MasterType::surface)
          for (const auto &name : Utilities::split_string_list(p.master, ','))
            for (unsigned int b = 0; b < scene.bodies.size(); ++b)
              if (name.rfind(scene.bodies[b].name + ".", 0) == 0)
                master_modulus = std::min(master_modulus,
                                          elasticity.youngs_modulus_of_body(b));
        bool   node_based    = false;
        double slave_modulus = 0.;
        pair.nodes   = find_slave_nodes(p, path, node_based, slave_modulus);
        pair.modulus = std::min(slave_modulus, master_modulus);
        // Under MPI each process holds the master facets within reach of
        // its slave nodes (R15.2): a search reaches 1.5 facets of either
        // side from a node (a mortar segment: its slave facet and 1.5 of
        // it around), taken 4 times; finite sliding may move that far
        // again before follow() gathers anew.
        if (surface && Utilities::MPI::n_mpi_processes(comm) > 1)
          {
            double slave_size = 0.;
            for (const auto &node : pair.nodes)
              slave_size = std::max(slave_size, node.size);
            const double size  = std::max(surface->facet_size(),
                                         Utilities::MPI::max(slave_size, comm));
            pair.gather_reach  = 4. * size + 2. * surface->facet_size();
            pair.gather_margin = p.sliding == "finite" ? 4. * size : 0.;
            surface->gather_near(VectorType(),
                                 slave_region(pair, VectorType()));
            pair.gathered_at.assign(dim * pair.nodes.size(), 0.);
            pair.gathers = 1;
          }
        // A slave much stiffer than its deformable master: the usual
        // advice (the softer body is the slave) exists because the master's
        // nodes are not constrained, and a soft master passes through a
        // stiff slave between its constraints.
        const double slave_max = Utilities::MPI::max(slave_modulus, comm);
        if (std::isfinite(master_modulus) &&
            slave_max >= stiff_slave_ratio * master_modulus &&
            Utilities::MPI::this_mpi_process(comm) == 0)
          {
            std::ostringstream text;
            text << "warning: contact pair '" << p.name
                 << "': the slave surface '" << p.slave << "' (Young's modulus "
                 << slave_max << ") is " << std::setprecision(2)
                 << slave_max / master_modulus
                 << " times stiffer than the master surface '" << p.master
                 << "' (" << master_modulus
                 << "). A soft master passes through a stiff slave between "
                    "its constrained points: the contact pressure "
                    "concentrates at the slave's nodes and Newton's active "
                    "set may cycle (more so where the slave's mesh is the "
                    "finer). Make the softer body the slave (swap 'Slave' "
                    "and 'Master').";
            messages.push_back(text.str());
          }
        if (!std::isfinite(pair.modulus))
          pair.modulus = max_youngs_modulus;
        for (auto &node : pair.nodes)
          {
            // A node-based slave scales c with its size^(dim-1), not with
            // its nominal area 1, so that iterations stay unit-free.
            node.c = pair.modulus *
                     (node_based ? std::pow(node.size, dim - 1) : node.area) /
                     node.size;
            const double stiffness = p.penalty_stiffness > 0 ?
                                       p.penalty_stiffness :
                                       1000. * pair.modulus / node.size;
            node.k                 = stiffness * node.area;
          }
        const unsigned int n_global =
          Utilities::MPI::sum(static_cast<unsigned int>(pair.nodes.size()),
                              comm);
        require(n_global > 0,
                "Contact pair '" + p.name + "': the slave surface '" + p.slave +
                  "' has no nodes" +
                  (scene.analysis == AnalysisType::axisymmetric ?
                     std::string(" with area (a surface on the axis r = 0 "
                                 "of an axisymmetric scene has none); name "
                                 "a surface off the axis as 'Slave'") :
                     std::string()) +
                  ".");
        // A slave surface without area (in an axisymmetric scene, one on
        // the axis r = 0) carries no pressure: its nodes' constraints were
        // round-off (CPRESS 4.85e16 at one node, a penetrating node with
        // no force, exit 0). Its area against that of facets of its size.
        if (!node_based)
          {
            double area = 0., nominal = 0.;
            for (const auto &node : pair.nodes)
              {
                area += std::abs(node.area);
                nominal += std::pow(node.size, dim - 1) *
                           (scene.analysis == AnalysisType::axisymmetric ?
                              2. * numbers::PI * node.size :
                              1.);
              }
            area    = Utilities::MPI::sum(area, comm);
            nominal = Utilities::MPI::sum(nominal, comm);
            require(area > 1e-8 * nominal,
                    "Contact pair '" + p.name + "': the slave surface '" +
                      p.slave + "' has no area" +
                      (scene.analysis == AnalysisType::axisymmetric ?
                         std::string(" (it lies on the axis r = 0 of this "
                                     "axisymmetric scene)") :
                         std::string()) +
                      ", so it carries no contact pressure. Name a surface "
                      "off the axis as 'Slave'.");
          }
        if (surface)
          {
            std::set<types::global_dof_index> master_dofs;
            for (const auto &m : surface->get_nodes())
              master_dofs.insert(m.dofs[0]);
            for (const auto &node : pair.nodes)
              {
                std::ostringstream x;
                x << node.X;
                require(master_dofs.count(node.dofs[0]) == 0,
                        "Contact pair '" + p.name + "': the slave node at (" +
                          x.str() + ") is also a node of the master surface '" +
                          p.master +
                          "'; slave and master must not share nodes (use "
                          "surfaces of different bodies, or split the "
                          "surface).");
              }
          }
        PairContext<dim> context{scene,
                                 elasticity,
                                 comm,
                                 p,
                                 path,
                                 [this](const std::vector<std::string> &nodes,
                                        const std::string              &before,
                                        const std::string              &after) {
                                   report(nodes, before, after);
                                 },
                                 [this](const std::string &text) {
                                   if (Utilities::MPI::this_mpi_process(comm) ==
                                       0)
                                     messages.push_back(text);
                                 }};
        pair.formulation =
          make_formulation<dim>(context, std::move(master), std::move(surface));
        pair.enforcement = make_enforcement<dim>(p);
        pairs.push_back(std::move(pair));
        // The formulation keeps a reference to the nodes: set up in place.
        pairs.back().formulation->setup(pairs.back().nodes);
        // Quadratic facets between two deformable bodies with a node-wise
        // constraint: the pressure a user reads is not to be trusted
        // (doc/theory/node-to-surface.md, "Quadratic elements between two
        // deformable bodies"). A master 100 times stiffer than the slave
        // hardly deforms under the slave nodes' point forces (1e6 times:
        // p0 within 0.1 % of Hertz's).
        pairs.back().compliant_master =
          pairs.back().formulation->master_surface() != nullptr &&
          master_modulus < quadratic_master_ratio * slave_max &&
          p.formulation != "mortar";
        if (pairs.back().compliant_master &&
            pairs.back().formulation->master_surface()->degree() == 2 &&
            Utilities::MPI::this_mpi_process(comm) == 0)
          messages.push_back(
            "warning: contact pair '" + p.name + "': '" + p.formulation +
            "' with quadratic elements between two deformable bodies: each "
            "slave node's force acts at one point of the master's quadratic "
            "facets, and the nodal contact pressure (CPRESS) zigzags between "
            "corner and mid-side slave nodes unless the slave's facets are "
            "clearly shorter than the master's where they touch (two-"
            "materials Hertz: 17-21 % from node to node and the peak "
            "pressure 5-9 % high; with the slave's facets 1.6 times shorter, "
            "1-2 %). Forces and displacements are not affected. For the "
            "pressure field, use 'Formulation = mortar' (the coarser side as "
            "slave), or element degree 1 (doc/theory/node-to-surface.md).");
        // Under MPI: how the pair is split between the processes.
        const unsigned int n_processes = Utilities::MPI::n_mpi_processes(comm);
        if (n_processes > 1)
          {
            const auto        &nodes = pairs.back().nodes;
            std::ostringstream text;
            text << "contact pair '" << p.name << "': " << n_global
                 << " slave nodes on "
                 << Utilities::MPI::sum(nodes.empty() ? 0u : 1u, comm) << " of "
                 << n_processes << " processes";
            if (const auto *s = pairs.back().formulation->master_surface())
              {
                const unsigned int held = s->get_facets().size();
                text << "; the master surface's " << s->n_facets_global()
                     << " facets on " << s->n_owners()
                     << " process(es); each process holds those within "
                     << pairs.back().gather_reach + pairs.back().gather_margin
                     << " of its slave nodes: "
                     << Utilities::MPI::min(held, comm) << " to "
                     << Utilities::MPI::max(held, comm);
                if (pairs.back().gather_margin > 0.)
                  text << ", gathered again after the nodes moved by "
                       << 0.5 * pairs.back().gather_margin;
              }
            if (Utilities::MPI::this_mpi_process(comm) == 0)
              messages.push_back(text.str());
          }
      }

    // Number the multiplier blocks: each node gets block_size() of them,
    // this process's block follows those of the lower ranks.
    types::global_dof_index n_local = 0;
    for (const auto &pair : pairs)
      n_local += pair.nodes.size() * pair.enforcement->block_size();
    types::global_dof_index offset = 0;
    MPI_Exscan(&n_local, &offset, 1, DEAL_II_DOF_INDEX_MPI_TYPE, MPI_SUM, comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      offset = 0;
    total_multipliers = Utilities::MPI::sum(n_local, comm);
    multipliers       = IndexSet(first_multiplier + total_multipliers);
    multipliers.add_range(first_multiplier + offset,
                          first_multiplier + offset + n_local);
    types::global_dof_index next = first_multiplier + offset;
    update_read_ghosts();
    for (auto &pair : pairs)
      if (pair.enforcement->block_size() > 0)
        for (auto &node : pair.nodes)
          {
            node.multiplier = next;
            next += pair.enforcement->block_size();
          }
  }

  template <int dim>
  void
  Contact<dim>::update_read_ghosts()
  {
    // Under MPI: the DoFs the formulations read beyond this process's
    // own (master nodes, mortar slave facets), imported by view().
    std::vector<types::global_dof_index> read;
    for (const auto &pair : pairs)
      pair.formulation->read_dofs(read);
    std::sort(read.begin(), read.end());
    read.erase(std::unique(read.begin(), read.end()), read.end());
    read_ghosts = IndexSet(multipliers.size());
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      read_ghosts.add_indices(read.begin(), read.end());
    read_ghosts.compress();
    import_ghosts =
      Utilities::MPI::max(read_ghosts.n_elements() > 0 ? 1 : 0, comm) > 0;
    ghosted.clear();
    ghosts_changed = true;
  }

  template <int dim>
  const VectorType &
  Contact<dim>::view(const VectorType &U) const
  {
    if (!import_ghosts || U.size() == 0)
      return U;
    const bool other =
      ghosted.size() != U.size() ||
      ghosted.locally_owned_elements() != U.locally_owned_elements();
    if (Utilities::MPI::max(other ? 1 : 0, comm) > 0 || ghosts_changed)
      ghosted.reinit(U.locally_owned_elements(), read_ghosts, comm);
    ghosts_changed = false;
    ghosted        = U;
    return ghosted;
  }

  template <int dim>
  std::vector<BoundingBox<dim>>
  Contact<dim>::slave_region(const Pair &pair, const VectorType &U) const
  {
    std::vector<Point<dim>> x;
    for (const auto &node : pair.nodes)
      {
        x.push_back(node.X);
        if (U.size() > 0)
          for (unsigned int d = 0; d < dim; ++d)
            x.back()[d] += U[node.dofs[d]];
      }
    return covering_boxes(x, pair.gather_margin + pair.gather_reach);
  }

  template <int dim>
  double
  Contact<dim>::motion_since_gather(const Pair &pair, const VectorType &U) const
  {
    double slave = 0.;
    for (unsigned int i = 0; i < pair.nodes.size(); ++i)
      for (unsigned int d = 0; d < dim; ++d)
        slave = std::max(slave,
                         std::abs(U[pair.nodes[i].dofs[d]] -
                                  pair.gathered_at[dim * i + d]));
    const double master = pair.formulation->master_surface()->own_motion(U);
    // Per component: a node moves at most sqrt(dim) times its largest.
    return std::sqrt(double(dim)) * (Utilities::MPI::max(slave, comm) +
                                     Utilities::MPI::max(master, comm));
  }

  template <int dim>
  bool
  Contact<dim>::follow(const VectorType &U_in)
  {
    if (Utilities::MPI::n_mpi_processes(comm) == 1 || U_in.size() == 0)
      return false;
    bool any = false;
    for (auto &pair : pairs)
      {
        if (!pair.formulation->slides() || pair.gather_margin == 0. ||
            pair.formulation->master_surface() == nullptr)
          continue;
        const VectorType &U     = view(U_in);
        const double      moved = motion_since_gather(pair, U);
        if (moved <= 0.5 * pair.gather_margin)
          continue;
        pair.formulation->regather(U, slave_region(pair, U));
        for (unsigned int i = 0; i < pair.nodes.size(); ++i)
          for (unsigned int d = 0; d < dim; ++d)
            pair.gathered_at[dim * i + d] = U[pair.nodes[i].dofs[d]];
        ++pair.gathers;
        const unsigned int held =
          pair.formulation->master_surface()->get_facets().size();
        const unsigned int fewest = Utilities::MPI::min(held, comm);
        const unsigned int most   = Utilities::MPI::max(held, comm);
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          {
            std::ostringstream text;
            text << "contact pair '" << pair.parameters->name
                 << "': master facets gathered again (gather " << pair.gathers
                 << "; slave nodes and master moved by " << moved
                 << " since the last): each process holds " << fewest << " to "
                 << most << " of "
                 << pair.formulation->master_surface()->n_facets_global();
            messages.push_back(text.str());
          }
        any = true;
      }
    if (any)
      {
        update_read_ghosts();
        gathered = true;
      }
    return any;
  }

  template <int dim>
  void
  Contact<dim>::add_sparsity(DynamicSparsityPattern &dsp)
  {
    for (auto &pair : pairs)
      {
        if (last_displacement.size() > 0)
          pair.formulation->move(last_displacement);
        const unsigned int block = pair.enforcement->block_size();
        for (unsigned int i = 0; i < pair.nodes.size(); ++i)
          {
            const auto                          &node = pair.nodes[i];
            std::vector<types::global_dof_index> idx(node.dofs.begin(),
                                                     node.dofs.end());
            for (unsigned int j = 0; j < block; ++j)
              idx.push_back(node.multiplier + j);
            pair.formulation->couplings(i, last_displacement, idx);
            // Through the constraints: a slave node at a hanging node
            // couples with the DoFs it is constrained to.
            elasticity.update_constraints().add_entries_local_to_global(idx,
                                                                        dsp,
                                                                        false);
          }
      }
  }

  template <int dim>
  bool
  Contact<dim>::needs_new_pattern(const VectorType &U_in)
  {
    follow(U_in);
    const VectorType &U       = view(U_in);
    bool              outside = gathered;
    gathered                  = false;
    for (const auto &pair : pairs)
      {
        pair.formulation->move(U);
        for (unsigned int i = 0; i < pair.nodes.size() && !outside; ++i)
          outside =
            pair.formulation->outside_pattern(i,
                                              pair.formulation->evaluate(i, U));
      }
    outside = Utilities::MPI::max(outside ? 1 : 0, comm) > 0;
    if (outside)
      {
        // Positions for add_sparsity().
        last_displacement = U;
      }
    return outside;
  }

  template <int dim>
  std::vector<Constraint<dim>>
  Contact<dim>::constraints(const Pair &pair, const VectorType &U) const
  {
    pair.formulation->move(U);
    std::vector<Constraint<dim>> s;
    s.reserve(pair.nodes.size());
    typename Formulation<dim>::Linearization l;
    l.derivatives = false;
    for (unsigned int i = 0; i < pair.nodes.size(); ++i)
      {
        s.push_back(pair.formulation->evaluate(i, U));
        if (s.back().found() && has_prescribed_dof(pair.nodes[i]))
          {
            pair.formulation->linearize(i, s.back(), U, l);
            mark_prescribed(s.back(), l);
          }
      }
    return s;
  }

  template <int dim>
  bool
  Contact<dim>::has_prescribed_dof(const SlaveNode<dim> &node) const
  {
    const auto &c = elasticity.update_constraints();
    return std::any_of(node.dofs.begin(),
                       node.dofs.end(),
                       [&c](const types::global_dof_index dof) {
                         const auto *line = c.get_constraint_entries(dof);
                         return line != nullptr && line->empty();
                       });
  }

  template <int dim>
  void
  Contact<dim>::mark_prescribed(
    Constraint<dim>                                &s,
    const typename Formulation<dim>::Linearization &l) const
  {
    // A Dirichlet line has no entries (hanging nodes have theirs, resolved
    // to unconstrained DoFs by close()).
    const auto &c   = elasticity.update_constraints();
    double      all = 0., free = 0.;
    for (unsigned int a = 0; a < l.dofs.size(); ++a)
      {
        const double g2 = l.force(a) * l.force(a);
        all += g2;
        const auto *line = c.get_constraint_entries(l.dofs[a]);
        if (line == nullptr || !line->empty())
          free += g2;
      }
    if (all > 0. && free <= 1e-12 * all)
      s.outcome = Outcome::prescribed;
  }

  template <int dim>
  std::vector<typename ContactEnforcement<dim>::Force>
  Contact<dim>::forces(const Pair                         &pair,
                       const std::vector<Constraint<dim>> &s,
                       const VectorType                   &U) const
  {
    std::vector<typename ContactEnforcement<dim>::Force> f;
    f.reserve(s.size());
    for (unsigned int i = 0; i < s.size(); ++i)
      f.push_back(pair.enforcement->force(pair.nodes[i], s[i], U));
    return f;
  }

  template <int dim>
  std::vector<typename ActiveSetMonitor<dim>::Status>
  Contact<dim>::status(const VectorType &U_in) const
  {
    const VectorType                                   &U = view(U_in);
    std::vector<typename ActiveSetMonitor<dim>::Status> result;
    for (const auto &pair : pairs)
      {
        const auto s = constraints(pair, U);
        const auto f = forces(pair, s, U);
        for (unsigned int i = 0; i < s.size(); ++i)
          {
            typename ActiveSetMonitor<dim>::Status status;
            status.closed   = f[i].closed;
            status.X        = pair.nodes[i].X;
            const int piece = pair.formulation->holdable_piece(s[i]);
            status.holdable = piece >= 0;
            status.piece    = piece;
            // (With a margin for the round-off of the covered weight.)
            status.at_master_end = s[i].coverage < 1. - 1e-6;
            result.push_back(status);
          }
      }
    return result;
  }

  template <int dim>
  void
  Contact<dim>::hold(const std::vector<Hold> &holds)
  {
    for (const auto &[k, piece, partner] : holds)
      {
        unsigned int first = 0;
        for (auto &pair : pairs)
          {
            if (k < first + pair.nodes.size())
              {
                pair.formulation->hold(k - first, piece, partner);
                break;
              }
            first += pair.nodes.size();
          }
      }
  }

  template <int dim>
  void
  Contact<dim>::release_holds()
  {
    for (auto &pair : pairs)
      pair.formulation->release_holds();
  }

  template <int dim>
  double
  Contact<dim>::held_gap_error(const VectorType &U_in) const
  {
    const VectorType &U     = view(U_in);
    double            worst = 0.;
    for (const auto &pair : pairs)
      for (const auto &held : pair.formulation->held_gaps(constraints(pair, U)))
        worst = std::max(worst, held.error / held.facet_length);
    return Utilities::MPI::max(worst, comm);
  }

  template <int dim>
  unsigned int
  Contact<dim>::n_held() const
  {
    unsigned int n = 0;
    for (const auto &pair : pairs)
      n += pair.formulation->n_held();
    return Utilities::MPI::sum(n, comm);
  }

  template <int dim>
  double
  Contact<dim>::held_force_effect(const VectorType &U_in) const
  {
    const VectorType &U     = view(U_in);
    double            worst = 0.;
    for (const auto &pair : pairs)
      {
        const auto s = constraints(pair, U);
        worst = std::max(worst, held_force_effect(pair, s, forces(pair, s, U)));
      }
    return worst;
  }

  template <int dim>
  std::vector<
    std::pair<types::global_dof_index, std::vector<types::global_dof_index>>>
  Contact<dim>::condensable_multipliers(std::string &why_not) const
  {
    std::vector<
      std::pair<types::global_dof_index, std::vector<types::global_dof_index>>>
      blocks;
    why_not.clear();
    // Under MPI each process checks its own slave nodes; the first reason
    // in rank order holds for every process, so that all of them take the
    // same solver.
    const auto agreed = [this, &why_not, &blocks]() {
      why_not = first_failure_on_any_process(why_not, comm);
      if (!why_not.empty())
        blocks.clear();
      return blocks;
    };
    std::set<types::global_dof_index> masters, slaves;
    for (const auto &pair : pairs)
      if (const auto *surface = pair.formulation->master_surface())
        {
          for (const auto &node : surface->get_nodes())
            masters.insert(node.dofs.begin(), node.dofs.end());
          masters.insert(surface->own_dofs().begin(),
                         surface->own_dofs().end());
        }
    // A slave node whose DoFs are constrained (a hanging node whose parents
    // are not all slave nodes of the pair; condense_hanging_nodes()) is a
    // block too: while it is open the elimination takes its force in its
    // parents' rows; a Jacobian where it is closed goes to the direct
    // solver (MultiplierCondensation::NotCondensable).
    for (const auto &pair : pairs)
      {
        if (pair.enforcement->block_size() == 0)
          continue;
        // Penalty: each multiplier follows from the displacements (its row
        // has a diagonal), whatever rows its force reaches; no node of its
        // own is needed.
        if (pair.enforcement->compliant())
          {
            for (const auto &node : pair.nodes)
              for (unsigned int j = 0; j < pair.enforcement->block_size(); ++j)
                blocks.emplace_back(node.multiplier + j,
                                    std::vector<types::global_dof_index>());
            continue;
          }
        const std::string name = "contact pair '" + pair.parameters->name + "'";
        if (pair.enforcement->block_size() != 1 ||
            !pair.formulation->force_on_own_node())
          {
            why_not = "'" + pair.formulation->name() + "' (" + name +
                      ") spreads each contact force over several slave nodes";
            return agreed();
          }
        for (const auto &node : pair.nodes)
          {
            for (const auto d : node.dofs)
              if (masters.count(d) > 0 || !slaves.insert(d).second)
                {
                  std::ostringstream x;
                  x << node.X;
                  why_not = "the slave node at (" + x.str() + ") of " + name +
                            " is on two contact surfaces";
                  return agreed();
                }
            blocks.emplace_back(node.multiplier,
                                std::vector<types::global_dof_index>(
                                  node.dofs.begin(), node.dofs.end()));
          }
      }
    std::sort(blocks.begin(), blocks.end());
    return agreed();
  }

  template <int dim>
  void
  Contact<dim>::set_time(const double t)
  {
    time = t;
    for (auto &pair : pairs)
      pair.formulation->set_time(t);
  }

  template <int dim>
  void
  Contact<dim>::assemble(const VectorType                &U_in,
                         VectorType                      *F,
                         MatrixType                      *J,
                         const AffineConstraints<double> &constraints) const
  {
    const VectorType &U = view(U_in);
    // Under MPI: an iterate whose searches could reach master facets not
    // held here (gathered around where the nodes were, follow()) would
    // not be the serial run's residual.
    for (const auto &pair : pairs)
      if (pair.formulation->slides() && pair.gather_margin > 0. && U.size() > 0)
        if (const double moved = motion_since_gather(pair, U);
            moved > pair.gather_margin)
          {
            std::ostringstream text;
            text << "contact pair '" << pair.parameters->name
                 << "': the slave nodes and the master moved by " << moved
                 << " in one Newton step, beyond the " << pair.gather_margin
                 << " for which each process holds the master facets they "
                    "can reach";
            throw std::runtime_error(text.str());
          }
    std::string failure; // a projection that failed on this process
    typename Formulation<dim>::Linearization l;
    l.derivatives = J != nullptr;
    Vector<double>                       rhs;
    FullMatrix<double>                   K;
    std::vector<types::global_dof_index> idx;
    for (const auto &pair : pairs)
      {
        const auto &formulation = *pair.formulation;
        const auto &enforcement = *pair.enforcement;
        formulation.move(U);
        for (unsigned int i = 0; i < pair.nodes.size(); ++i)
          {
            const auto     &node = pair.nodes[i];
            Constraint<dim> s;
            try
              {
                s = formulation.evaluate(i, U);
                if (s.found())
                  {
                    formulation.linearize(i, s, U, l);
                    if (has_prescribed_dof(node))
                      mark_prescribed(s, l);
                  }
              }
            catch (const UndefinedNormal &e)
              {
                failure = std::string(e.what()) +
                          " (the increment moved the master by about its "
                          "radius against the slave)";
                continue;
              }
            catch (const std::exception &e)
              {
                // Finish the loop so that every process reaches compress().
                failure = e.what();
                continue;
              }
            const auto   f = enforcement.force(node, s, U);
            const double w = J ? stabilization_weight(node, s, f) : 0.;
            enforcement.local(
              node, s, f, l, pair.parameters->symmetrized, w, idx, rhs, K);
            if (idx.empty())
              continue;
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
    throw_on_any_process(failure, comm);
  }

  template <int dim>
  double
  Contact<dim>::stabilization_weight(
    const SlaveNode<dim>                          &node,
    const Constraint<dim>                         &s,
    const typename ContactEnforcement<dim>::Force &f) const
  {
    if (!(stabilize > 0.) || f.closed || !s.found() || !(s.gap >= 0.) ||
        s.gap >= node.size)
      return 0.;
    const double w = 1. - s.gap / node.size;
    return stabilize * stabilization * node.c * w * w;
  }

  template <int dim>
  double
  Contact<dim>::round_off_floor() const
  {
    // Row scale (set_scaling()) x c x 10 eps |X|: a gap computed from
    // positions of magnitude |X| (reference, plus displacements of the
    // scene's size at most) to a few epsilon of them.
    double floor = 0.;
    for (const auto &pair : pairs)
      for (const auto &node : pair.nodes)
        {
          double x = elasticity.length_scale();
          for (unsigned int d = 0; d < dim; ++d)
            x = std::max(x, std::abs(node.X[d]));
          floor =
            std::max(floor,
                     10. * std::numeric_limits<double>::epsilon() * x * node.c *
                       elasticity.residual_scale() *
                       elasticity.softest_youngs_modulus() / pair.modulus);
        }
    return Utilities::MPI::max(floor, comm);
  }

  template <int dim>
  void
  Contact<dim>::set_scaling(VectorType &residual_scale,
                            VectorType &solution_scale) const
  {
    // 1 / (E_min A_ref) times E_min / E_pair.
    for (const auto &pair : pairs)
      for (const auto &node : pair.nodes)
        for (unsigned int j = 0; j < pair.enforcement->block_size(); ++j)
          {
            const double scale = elasticity.residual_scale() *
                                 elasticity.softest_youngs_modulus() /
                                 pair.modulus;
            residual_scale[node.multiplier + j] = scale;
            solution_scale[node.multiplier + j] = scale;
          }
    residual_scale.compress(VectorOperation::insert);
    solution_scale.compress(VectorOperation::insert);
  }

  template <int dim>
  std::vector<std::pair<std::string, std::string>>
  Contact<dim>::statistics(const VectorType &U_in) const
  {
    const VectorType                                &U = view(U_in);
    std::vector<std::pair<std::string, std::string>> row;
    const char                                      *axis[] = {"x", "y", "z"};
    for (const auto &pair : pairs)
      {
        // R16.3: what the contact computation could not do at this state,
        // counted per step: projections that failed to converge, nodes
        // beyond the end of the master (open by definition), nodes without
        // an anchor (small sliding), nodes held on one facet, constraints
        // that fell back to a simpler formulation.
        unsigned int active = 0, failed = 0, beyond = 0, unanchored = 0,
                     prescribed   = 0;
        unsigned int incomplete   = 0;
        double       normal_force = 0, penetration = 0;
        // The slave nodes' own penetration (for averaged constraints, not
        // their constraints' gap).
        double         node_penetration = 0;
        Tensor<1, dim> force;
        const auto     s = constraints(pair, U);
        const auto     f = forces(pair, s, U);
        for (unsigned int i = 0; i < s.size(); ++i)
          {
            active += f[i].closed ? 1 : 0;
            failed += s[i].outcome == Outcome::failed ? 1 : 0;
            incomplete += s[i].found() && s[i].projection.incomplete ? 1 : 0;
            beyond += s[i].outcome == Outcome::beyond_end ? 1 : 0;
            unanchored += s[i].outcome == Outcome::unanchored ? 1 : 0;
            prescribed += s[i].outcome == Outcome::prescribed ? 1 : 0;
            normal_force += f[i].lambda;
            force += f[i].lambda * s[i].normal;
            if (s[i].found() || s[i].outcome == Outcome::prescribed)
              penetration = std::max(penetration, -s[i].gap);
            if (s[i].found())
              node_penetration =
                std::max(node_penetration, -pair.formulation->own_gap(i, s[i]));
          }
        // The force on the master surface of a body (R14.6: the exact
        // reaction of the slave's): lambda times the force direction G in
        // the rows of the master surface's DoFs (the linearization lists
        // DoFs node by node, components in order; its slave DoFs may be
        // those of another process's nodes, in a surface-to-surface region
        // or a mortar facet cut by the partition).
        Tensor<1, dim> master_force;
        if (const auto *surface = pair.formulation->master_surface())
          {
            std::set<types::global_dof_index> master_dofs;
            for (const auto &node : surface->get_nodes())
              master_dofs.insert(node.dofs.begin(), node.dofs.end());
            typename Formulation<dim>::Linearization l;
            l.derivatives = false;
            for (unsigned int i = 0; i < s.size(); ++i)
              if (s[i].found() && f[i].lambda != 0.)
                {
                  pair.formulation->linearize(i, s[i], U, l);
                  for (unsigned int a = 0; a < l.dofs.size(); ++a)
                    if (master_dofs.count(l.dofs[a]) > 0)
                      master_force[a % dim] += f[i].lambda * l.force(a);
                }
            master_force = Utilities::MPI::sum(master_force, comm);
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
        if (pair.formulation->master_surface() != nullptr)
          for (unsigned int d = 0; d < dim; ++d)
            row.emplace_back(p + "master_force_" + axis[d],
                             format_number(master_force[d]));
        double max_slip = 0;
        for (const double slip : pair.formulation->slip())
          max_slip = std::max(max_slip, slip);
        row.emplace_back(p + "max_slip",
                         format_number(Utilities::MPI::max(max_slip, comm)));
        row.emplace_back(p + "max_penetration",
                         format_number(Utilities::MPI::max(penetration, comm)));
        row.emplace_back(p + "node_penetration",
                         format_number(
                           Utilities::MPI::max(node_penetration, comm)));
        const auto count = [&](const std::string &name, const unsigned int n) {
          row.emplace_back(p + name,
                           std::to_string(Utilities::MPI::sum(n, comm)));
        };
        count("projection_failed", failed);
        count("projection_incomplete", incomplete);
        count("beyond_end", beyond);
        count("unanchored", unanchored);
        count("prescribed", prescribed);
        count("held", pair.formulation->n_held());
        row.emplace_back(p + "held_force_effect",
                         format_number(held_force_effect(pair, s, f)));
        count("fallbacks", pair.formulation->n_fallbacks());
      }
    return row;
  }

  template <int dim>
  double
  Contact<dim>::held_force_effect(
    const Pair                                                 &pair,
    const std::vector<Constraint<dim>>                         &s,
    const std::vector<typename ContactEnforcement<dim>::Force> &f) const
  {
    double largest = 0., effect = 0.;
    for (const auto &force : f)
      largest = std::max(largest, std::abs(force.lambda));
    for (const auto &held : pair.formulation->held_gaps(s))
      {
        const auto  &node      = pair.nodes[held.node];
        const double stiffness = pair.enforcement->compliant() && node.k > 0. ?
                                   1. / (1. / node.c + 1. / node.k) :
                                   node.c;
        effect                 = std::max(effect, stiffness * held.error);
      }
    largest = Utilities::MPI::max(largest, comm);
    effect  = Utilities::MPI::max(effect, comm);
    return effect > 0. && largest > 0. ? effect / largest : 0.;
  }

  template <int dim>
  double
  Contact<dim>::largest_master_motion(const std::vector<double> &factors) const
  {
    double largest = 0.;
    for (const auto &pair : pairs)
      if (const auto *master = pair.formulation->rigid_master())
        for (const auto &node : pair.nodes)
          for (const double t : factors)
            largest =
              std::max(largest, (master->move(node.X, 0., t) - node.X).norm());
    return Utilities::MPI::max(largest, comm);
  }

  template <int dim>
  std::string
  Contact<dim>::passed_through(const VectorType &U_old,
                               const VectorType &U_new,
                               const double      t_old,
                               const double      t_new) const
  {
    std::string why;
    for (const auto &pair : pairs)
      {
        const auto *master = pair.formulation->rigid_master();
        if (master == nullptr)
          continue;
        unsigned int n       = 0;
        double       deepest = 0.; // relative to the node's facet size
        for (const auto &node : pair.nodes)
          {
            if (!(node.size > 0.))
              continue;
            Point<dim> x_old = node.X, x_new = node.X;
            for (unsigned int d = 0; d < dim; ++d)
              {
                x_old[d] += U_old[node.dofs[d]];
                x_new[d] += U_new[node.dofs[d]];
              }
            const double depth = master->passage_depth(
              x_old, t_old, x_new, t_new, 1e-6 * node.size);
            // Deeper than the node's facet size (a node that slides round
            // the master at a small gap dips in by the sagitta of its path,
            // doc/theory/nonlinear-solution.md), or than half the radius
            // where the master is smaller than a facet: a sagitta of R / 2
            // needs a slide of a whole diameter. (A circle of radius 0.2 on
            // facets of 0.25, moved from 0.1 above a node to below its top
            // in one increment, lifted the block, exit 0, until 2026-12-07.)
            const double limit =
              std::min(node.size, 0.5 * master->curvature_radius());
            if (depth > limit)
              {
                ++n;
                deepest = std::max(deepest, depth / node.size);
              }
          }
        n       = Utilities::MPI::sum(n, comm);
        deepest = Utilities::MPI::max(deepest, comm);
        if (n > 0 && why.empty())
          {
            std::ostringstream text;
            text << "the rigid master of contact pair '"
                 << pair.parameters->name << "' passed through " << n
                 << " slave node(s) within the increment (open after it, "
                    "or in contact on the master's far side; their paths "
                    "relative to the master run up to "
                 << std::setprecision(3) << deepest
                 << " slave facet sizes deep through it)";
            why = text.str();
          }
      }
    return why;
  }

  template <int dim>
  void
  Contact<dim>::commit_step(const VectorType &U_in,
                            const double      t_old,
                            const double      t_new)
  {
    const VectorType &U = view(U_in);
    std::vector<std::vector<std::pair<unsigned int, Tensor<1, dim>>>>
      closed_nodes;
    for (auto &pair : pairs)
      {
        const auto        s = constraints(pair, U);
        const auto        f = forces(pair, s, U);
        std::vector<bool> closed;
        closed_nodes.emplace_back();
        for (unsigned int i = 0; i < f.size(); ++i)
          {
            closed.push_back(f[i].closed);
            if (f[i].closed)
              closed_nodes.back().emplace_back(i, s[i].normal);
          }
        finer_master_facets(pair, s, closed);
        hidden_penetration(pair, s, closed);
        if (!pair.prescribed_said)
          {
            std::vector<std::string> list;
            for (unsigned int i = 0; i < s.size(); ++i)
              if (s[i].outcome == Outcome::prescribed)
                {
                  std::ostringstream text;
                  text << "(" << pair.nodes[i].X << ")";
                  list.push_back(text.str());
                }
            pair.prescribed_said = Utilities::MPI::sum(list.size(), comm) > 0;
            report(list,
                   "warning: contact pair '" + pair.parameters->name +
                     "': a boundary condition prescribes the motion along "
                     "the contact normal of ",
                   " slave node(s), so contact is not enforced there: the "
                   "condition decides where they are (one that drives them "
                   "into the master leaves them there, in "
                   "'max_penetration') and its reaction carries their share "
                   "of the contact force (counted in statistics.csv as "
                   "'prescribed'); take them out of the condition or out "
                   "of the slave surface if contact should hold them (node "
                   "positions in the reference configuration)");
          }
        pair.formulation->commit_step(U, s, closed, t_old, t_new);
        // After the formulation's note on its held nodes (they stay held
        // until the next step starts).
        if (const double effect = held_force_effect(pair, s, f);
            effect > 1e-3 && Utilities::MPI::this_mpi_process(comm) == 0)
          {
            std::ostringstream text;
            text << "contact pair '" << pair.parameters->name
                 << "': the held nodes' gaps, measured to their facets' "
                    "planes instead of the master, may move their nodal "
                    "forces by up to "
                 << std::setprecision(2) << 100. * effect
                 << " % of the pair's largest (gap error times the contact "
                    "stiffness E A / h; statistics.csv: held_force_effect)";
            if (effect > 0.05)
              text << ": read their CPRESS with care, or smooth the master "
                      "('Smoothing fraction' > 0) or use 'Formulation = "
                      "mortar'";
            messages.push_back(text.str());
          }
      }
    // The history just committed may read DoFs of nodes this process does
    // not hold (Mortar: the last step's master nodes under the slave).
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      update_read_ghosts();
    unheld_motions(closed_nodes);
  }

  template <int dim>
  void
  Contact<dim>::unheld_motions(
    const std::vector<std::vector<std::pair<unsigned int, Tensor<1, dim>>>>
      &closed)
  {
    if (unheld_said)
      return;
    // The free motions do not change from step to step: found once.
    if (!free_motions_found)
      {
        free_motions       = elasticity.free_motions();
        free_motions_found = true;
      }
    const auto &motions = free_motions;
    // The body of a surface <body>.<surface> (a node-set slave has none).
    const auto body_of = [](const std::string &surface) {
      const auto dot = surface.find('.');
      return dot == std::string::npos ?
               std::string() :
               std::string(Utilities::trim(surface.substr(0, dot)));
    };
    std::vector<std::string> unheld;
    bool                     any_free = false;
    // Translations only: a round body's turn about its centre is held by
    // the facets of node to surface's master (its force acts along the
    // master's normal), not by the slave's radial normals, and at first
    // touch by almost nothing; that is not what this warning is about.
    for (unsigned int b = 0; b < motions.size(); ++b)
      for (const auto &m : motions[b])
        {
          if (m.rotation)
            continue;
          any_free                = true;
          const std::string &name = scene.bodies[b].name;
          Tensor<1, dim>     v;
          for (unsigned int d = 0; d < dim; ++d)
            v[d] = m.axis[d];
          // Along the motion: the reference slave normals and the
          // constraints' force directions (deformation tilts the latter
          // by about the strain).
          double slave = 0., force = 0., total = 0.;
          for (unsigned int k = 0; k < pairs.size(); ++k)
            {
              const auto &p       = *pairs[k].parameters;
              bool        touches = body_of(p.slave) == name;
              if (p.master_type == MasterType::surface)
                for (const auto &surface :
                     Utilities::split_string_list(p.master, ','))
                  touches = touches || body_of(surface) == name;
              if (!touches)
                continue;
              for (const auto &[i, normal] : closed[k])
                {
                  const auto  &node = pairs[k].nodes[i];
                  const double n    = node.normal.norm();
                  if (!(n > 0.) || !(normal.norm() > 0.))
                    continue;
                  slave += std::pow(v * node.normal / n, 2);
                  force += std::pow(v * normal / normal.norm(), 2);
                  total += 1.;
                }
            }
          slave = Utilities::MPI::sum(slave, comm);
          force = Utilities::MPI::sum(force, comm);
          total = Utilities::MPI::sum(total, comm);
          // Reference normals within 1e-5 rad of perpendicular, force
          // directions within 1e-2 rad.
          if (total > 0. && slave <= 1e-10 * total && force <= 1e-4 * total)
            unheld.push_back("body '" + name + "': its " + m.text);
        }
    if (!any_free)
      unheld_said = true;
    if (unheld.empty())
      return;
    unheld_said = true;
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    std::string list;
    for (const auto &u : unheld)
      list += (list.empty() ? "" : "; ") + u;
    messages.push_back(
      "warning: only contact holds " + list +
      ", and the normal of every closed contact node on the body is "
      "perpendicular to that motion: frictionless contact transmits no "
      "force along it, so the solution is not unique in it (the body's "
      "position along it is whatever the linear solver picked, and may "
      "differ with the number of processes or the solver). Hold the body "
      "against it with a boundary condition (a displacement or symmetry "
      "condition on a surface or node set of it).");
  }

  template <int dim>
  void
  Contact<dim>::hidden_penetration(Pair                               &pair,
                                   const std::vector<Constraint<dim>> &s,
                                   const std::vector<bool>            &closed)
  {
    if (pair.hidden_said)
      return;
    // A pair with no closed constraint carries no force: any penetration
    // beyond a thousandth of a facet means that contact has begun unseen.
    const bool none_closed =
      Utilities::MPI::max(std::any_of(closed.begin(),
                                      closed.end(),
                                      [](const bool c) { return c; }) ?
                            1 :
                            0,
                          comm) == 0;
    const double ratio =
      none_closed ? 1e-3 : static_cast<double>(hidden_penetration_ratio);
    // (relative depth, depth, constraint's gap, position) of the deepest
    // node beyond the ratio whose constraint shows less than that.
    unsigned int          n = 0;
    std::array<double, 4> deepest{{0., 0., 0., 0.}};
    Point<dim>            where;
    for (unsigned int i = 0; i < s.size(); ++i)
      {
        const auto &node = pair.nodes[i];
        if (!s[i].found() || !(node.size > 0.))
          continue;
        const double depth = -pair.formulation->own_gap(i, s[i]);
        if (depth > ratio * node.size && depth > -s[i].gap + ratio * node.size)
          {
            ++n;
            if (depth / node.size > deepest[0])
              {
                deepest = {{depth / node.size, depth, s[i].gap, 0.}};
                where   = s[i].x;
              }
          }
      }
    n = Utilities::MPI::sum(n, comm);
    if (n == 0)
      return;
    pair.hidden_said = true;
    // The deepest over all processes, with its position.
    std::vector<double> mine(deepest.begin(), deepest.begin() + 3);
    for (unsigned int d = 0; d < dim; ++d)
      mine.push_back(where[d]);
    std::vector<double> best;
    for (const auto &v : Utilities::MPI::all_gather(comm, mine))
      if (best.empty() || v[0] > best[0])
        best = v;
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    std::ostringstream text;
    text << std::setprecision(3) << "warning: contact pair '"
         << pair.parameters->name << "': " << n
         << " slave node(s) penetrate the master by more than " << 100. * ratio
         << " % of their facet size beyond what their "
         << (none_closed ? "constraints show, and none is closed: the pair "
                           "carries no force" :
                           "constraints show")
         << "; the deepest at (";
    for (unsigned int d = 0; d < dim; ++d)
      text << (d ? ", " : "") << best[3 + d];
    text << ") by " << best[1] << " (" << 100. * best[0]
         << " % of its facet size; its constraint's gap is " << best[2]
         << "). A surface-to-surface constraint's gap is the weighted mean "
            "of the gaps over the node's region, which on a curved master "
            "lies about h^2 / (3 R) above the node's own: slave facets this "
            "coarse hide penetration, and contact that has begun "
            "(statistics column 'contact_"
         << pair.parameters->name
         << "_node_penetration'). Refine the slave surface, or use "
            "'Formulation = mortar' or 'node to surface'.";
    messages.push_back(text.str());
  }

  template <int dim>
  void
  Contact<dim>::finer_master_facets(Pair                               &pair,
                                    const std::vector<Constraint<dim>> &s,
                                    const std::vector<bool>            &closed)
  {
    const auto *surface = pair.formulation->master_surface();
    if (!pair.compliant_master || pair.finer_master_said || surface == nullptr)
      return;
    // Reference lengths: the meshes' own proportions, whatever the
    // deformation.
    // (ratio, tributary area) of each closed node: the median is taken
    // over the contact area, not over the nodes. A graded slave has many
    // small facets where it is fine and few large ones where the master is
    // finer, which carry much of the force (a 3D sphere on a graded block
    // slave: the count median 1.7, the area median above 2, the force 9 %
    // to 20 % low until 2026-12-06 without a word).
    std::vector<double> ratios;
    for (unsigned int i = 0; i < s.size(); ++i)
      if (const int f = pair.formulation->touched_facet(i, s[i]);
          closed[i] && f >= 0)
        {
          const auto &facet = surface->get_facets()[f];
          // Its diameter, as the slave nodes' sizes are their faces'.
          const auto &nodes  = surface->get_nodes();
          double      length = 0.;
          for (const auto a : facet.nodes)
            for (const auto b : facet.nodes)
              length = std::max(length, nodes[a].X.distance(nodes[b].X));
          if (length > 0.)
            {
              ratios.push_back(pair.nodes[i].size / length);
              ratios.push_back(std::max(pair.nodes[i].area, 0.));
            }
        }
    std::vector<std::pair<double, double>> all;
    double                                 total = 0.;
    for (const auto &part : Utilities::MPI::all_gather(comm, ratios))
      for (unsigned int k = 0; k + 1 < part.size(); k += 2)
        {
          all.emplace_back(part[k], part[k + 1]);
          total += part[k + 1];
        }
    if (all.empty() || !(total > 0.))
      return;
    std::sort(all.begin(), all.end());
    double median = all.back().first, below = 0.;
    for (const auto &[ratio, area] : all)
      if ((below += area) >= 0.5 * total)
        {
          median = ratio;
          break;
        }
    if (median < finer_master_ratio)
      return;
    pair.finer_master_said = true;
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    const auto        &p = *pair.parameters;
    std::ostringstream text;
    text << "warning: contact pair '" << p.name
         << "': where the slave nodes touch, the master's facets are "
         << std::setprecision(2) << median
         << " times shorter than the slave's (median over the contact area of "
         << all.size()
         << " closed nodes). Each slave node's force acts at one point of "
            "the deformable master, which deforms unevenly under these point "
            "forces: the nodal contact pressure (CPRESS) zigzags and its peak "
            "is high (two-materials Hertz, doc/theory/node-to-surface.md), "
            "and master nodes sink into the slave between its nodes, so that "
            "the pair's force errs too (a 3D sphere on a graded block: 20 % "
            "low). "
            "Make the surface with the shorter facets the slave, or use "
            "'Formulation = mortar'.";
    messages.push_back(text.str());
  }

  template <int dim>
  unsigned int
  Contact<dim>::close_touching_nodes(VectorType &U_out) const
  {
    const VectorType &U        = view(U_out);
    unsigned int      n_closed = 0;
    for (const auto &pair : pairs)
      {
        if (pair.enforcement->block_size() == 0)
          continue;
        // A state without constraints here (a slave node at the centre of
        // a rigid circle that moved by its radius in the increment) closes
        // none; the solve's first residual fails the step, collectively.
        std::vector<Constraint<dim>> s;
        std::string                  failure;
        try
          {
            s = constraints(pair, U);
          }
        catch (const UndefinedNormal &e)
          {
            failure = e.what();
          }
        if (!first_failure_on_any_process(failure, comm).empty())
          continue;
        const auto f = forces(pair, s, U);
        // A pair that carries a force already keeps its active set (that
        // of the last converged step).
        const bool loaded = std::any_of(f.begin(), f.end(), [](const auto &x) {
          return x.lambda > 0.;
        });
        if (Utilities::MPI::max(loaded ? 1 : 0, comm) > 0)
          continue;
        for (unsigned int i = 0; i < s.size(); ++i)
          {
            const auto &node = pair.nodes[i];
            if (s[i].found() && s[i].gap <= 0.01 * node.size)
              {
                U_out[node.multiplier] =
                  pair.enforcement->closing_multiplier(node, s[i].gap);
                ++n_closed;
              }
          }
      }
    U_out.compress(VectorOperation::insert);
    return Utilities::MPI::sum(n_closed, comm);
  }

  template <int dim>
  unsigned int
  Contact<dim>::check_initial_overclosure(const VectorType &U_in)
  {
    const VectorType &U     = view(U_in);
    unsigned int      total = 0;
    for (const auto &pair : pairs)
      {
        // A slave node at the centre of a rigid circle, cylinder or sphere
        // in the initial configuration: a misplaced master.
        std::vector<Constraint<dim>> s;
        std::string                  failure;
        try
          {
            s = constraints(pair, U);
          }
        catch (const UndefinedNormal &e)
          {
            failure = pair.formulation->rigid_master()->misplaced(e);
          }
        throw_first_failure<InputError>(failure, comm);
        // The deepest node beyond its facet size, as (depth / size, depth,
        // position) on every process.
        unsigned int                           n = 0;
        std::tuple<double, double, Point<dim>> deepest{0., 0., Point<dim>()};
        for (unsigned int i = 0; i < s.size(); ++i)
          {
            const auto  &node  = pair.nodes[i];
            const double depth = -s[i].gap;
            if (!s[i].found() || node.size <= 0. || !(depth > node.size))
              continue;
            ++n;
            if (depth / node.size > std::get<0>(deepest))
              deepest = {depth / node.size, depth, node.X};
          }
        n = Utilities::MPI::sum(n, comm);
        total += n;
        const auto all = Utilities::MPI::gather(comm, deepest, 0);
        if (n == 0 || Utilities::MPI::this_mpi_process(comm) != 0)
          continue;
        for (const auto &d : all)
          if (std::get<0>(d) > std::get<0>(deepest))
            deepest = d;
        const auto        &p = *pair.parameters;
        std::ostringstream text;
        text << std::setprecision(3) << "warning: contact pair '" << p.name
             << "': " << n << " slave node(s) of '" << p.slave
             << "' start inside the master by more than their facet size "
                "(the deepest by "
             << std::get<1>(deepest) << ", " << std::get<0>(deepest)
             << " times its facet size, at (";
        for (unsigned int d = 0; d < dim; ++d)
          text << (d ? ", " : "") << std::get<2>(deepest)[d];
        text << ")). The first load step pushes them out at once, with a "
                "large force. If the bodies should start apart or just "
                "touching, check the positions of the meshes";
        if (p.master_type == MasterType::rigid_circle ||
            p.master_type == MasterType::rigid_sphere)
          text << " and 'Contact pair " << p.name
               << "/Rigid master/Slave inside' (" << std::boolalpha
               << p.slave_inside << ": the slave is "
               << (p.slave_inside ? "inside" : "outside") << " the "
               << (p.master_type == MasterType::rigid_circle ? "circle" :
                                                               "sphere")
               << ")";
        else if (p.master_type == MasterType::rigid_plane)
          text << " and the direction of 'Contact pair " << p.name
               << "/Rigid master/Normal' (it points from the plane towards "
                  "the slave)";
        text << ".";
        messages.push_back(text.str());
      }
    return total;
  }

  template <int dim>
  std::vector<ContactPairFields<dim>>
  Contact<dim>::nodal_fields(const VectorType &U_in, const double t)
  {
    const VectorType                   &U = view(U_in);
    std::vector<ContactPairFields<dim>> result;
    for (auto &pair : pairs)
      {
        pair.formulation->set_time(t);
        const auto s = constraints(pair, U);
        const auto f = forces(pair, s, U);
        // The normal contact force on each slave node: its constraint's
        // force, or (surface to surface) its share of the forces of every
        // constraint whose region holds it.
        std::vector<double> nodal(pair.nodes.size(), 0.);
        std::vector<std::pair<types::global_dof_index, double>> elsewhere;
        for (unsigned int i = 0; i < s.size(); ++i)
          pair.formulation->distribute(i, f[i].lambda, nodal, elsewhere);
        // Under MPI: the shares of slave nodes of other processes (regions
        // cut by the partition) to their owners.
        if (Utilities::MPI::max(elsewhere.empty() ? 0 : 1, comm) > 0)
          {
            std::map<types::global_dof_index, unsigned int> mine;
            for (unsigned int i = 0; i < pair.nodes.size(); ++i)
              mine[pair.nodes[i].dofs[0]] = i;
            for (const auto &part : Utilities::MPI::all_gather(comm, elsewhere))
              for (const auto &[dof, share] : part)
                if (const auto it = mine.find(dof); it != mine.end())
                  nodal[it->second] += share;
          }
        // Gathered as numbers: X, x, COPEN, force, CPRESS, CSTATUS, CSLIP,
        // normal, tangents, slip components.
        constexpr unsigned int n_values = 3 * dim + 5 + (dim - 1) * (dim + 1);
        std::vector<double>    local;
        for (unsigned int i = 0; i < s.size(); ++i)
          {
            for (unsigned int d = 0; d < dim; ++d)
              local.push_back(pair.nodes[i].X[d]);
            for (unsigned int d = 0; d < dim; ++d)
              local.push_back(s[i].x[d]);
            local.push_back(s[i].gap);
            local.push_back(nodal[i]);
            // A node without tributary area (the corner node on the axis
            // of a quadratic axisymmetric facet: int N r dr = 0) has no
            // pressure of its own; marked here, it gets its nearest
            // neighbour's below.
            const auto &node = pair.nodes[i];
            local.push_back(node.without_area() ?
                              std::numeric_limits<double>::quiet_NaN() :
                              nodal[i] / node.area);
            local.push_back(f[i].closed ? 1. : 0.);
            local.push_back(pair.formulation->slip()[i]);
            for (unsigned int d = 0; d < dim; ++d)
              local.push_back(s[i].normal[d]);
            for (const auto &t : s[i].tangents)
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(t[d]);
            for (unsigned int a = 0; a < dim - 1; ++a)
              local.push_back(pair.formulation->slip_components()[i][a]);
          }
        ContactPairFields<dim> fields;
        fields.pair = pair.parameters->name;
        for (const auto &part : Utilities::MPI::gather(comm, local, 0))
          for (unsigned int k = 0; k + n_values <= part.size(); k += n_values)
            {
              const double          *v = &part[k];
              ContactNodeFields<dim> n;
              for (unsigned int d = 0; d < dim; ++d)
                n.X[d] = *v++;
              for (unsigned int d = 0; d < dim; ++d)
                n.x[d] = *v++;
              n.COPEN   = *v++;
              n.force   = *v++;
              n.CPRESS  = *v++;
              n.CSTATUS = *v++;
              n.CSLIP   = *v++;
              for (unsigned int d = 0; d < dim; ++d)
                n.normal[d] = *v++;
              for (auto &t : n.tangents)
                for (unsigned int d = 0; d < dim; ++d)
                  t[d] = *v++;
              for (unsigned int a = 0; a < dim - 1; ++a)
                n.CSLIP_components[a] = *v++;
              fields.nodes.push_back(n);
            }
        for (auto &n : fields.nodes)
          if (std::isnan(n.CPRESS))
            {
              double best = std::numeric_limits<double>::infinity();
              n.CPRESS    = 0.;
              for (const auto &m : fields.nodes)
                if (!std::isnan(m.CPRESS) && &m != &n &&
                    n.X.distance(m.X) < best)
                  {
                    best     = n.X.distance(m.X);
                    n.CPRESS = m.CPRESS;
                  }
            }
        result.push_back(std::move(fields));
      }
    return result;
  }

  template <int dim>
  double
  Contact<dim>::search_time() const
  {
    double total = 0.;
    for (const auto &pair : pairs)
      total += pair.formulation->search_time();
    return total;
  }

  template <int dim>
  const std::vector<typename SmallSliding<dim>::Anchor> &
  Contact<dim>::anchors(const unsigned int pair) const
  {
    const auto *small = dynamic_cast<const SmallSlidingFormulation<dim> *>(
      pairs[pair].formulation.get());
    Assert(small != nullptr, ExcMessage("not a small-sliding pair"));
    return small->get_anchors();
  }

  template <int dim>
  std::vector<std::string>
  Contact<dim>::active_effects() const
  {
    std::vector<std::string> e;
    for (const auto &pair : pairs)
      {
        const auto &p    = *pair.parameters;
        std::string name = pair.formulation->name();
        if (p.sliding == "small" && !scene.geometric_nonlinearity)
          name.replace(name.find("small sliding"),
                       std::string("small sliding").size(),
                       "infinitesimal sliding (small sliding in a "
                       "geometrically linear scene: planes and load-transfer "
                       "weights fixed)");
        e.push_back("contact pair " + p.name + " (" + name + ", slave " +
                    p.slave + " with " +
                    std::to_string(Utilities::MPI::sum(
                      static_cast<unsigned int>(pair.nodes.size()), comm)) +
                    " nodes, master " + p.master + ", " +
                    pair.enforcement->name() + ")");
      }
    return e;
  }

  template <int dim>
  std::vector<std::string>
  Contact<dim>::take_messages()
  {
    std::vector<std::string> m;
    std::swap(m, messages);
    return m;
  }

  template <int dim>
  void
  Contact<dim>::report(const std::vector<std::string> &nodes,
                       const std::string              &before,
                       const std::string              &after)
  {
    const auto all = Utilities::MPI::gather(comm, nodes, 0);
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    std::vector<std::string> list;
    for (const auto &part : all)
      list.insert(list.end(), part.begin(), part.end());
    if (list.empty())
      return;
    std::string text = before + std::to_string(list.size()) + after + ": ";
    for (unsigned int k = 0; k < list.size() && k < 20; ++k)
      text += (k ? ", " : "") + list[k];
    if (list.size() > 20)
      text += ", ...";
    messages.push_back(text);
  }

  template class Contact<2>;
  template class Contact<3>;
} // namespace glide
