#include <glide/contact/contact.h>
#include <glide/output/statistics.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>

#include <chrono>
#include <cmath>
#include <fstream>
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
    max_youngs_modulus       = elasticity.youngs_modulus_scale();
    clearance                = 1e-10 * elasticity.length_scale();
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

    for (const auto &p : scene.contact_pairs)
      {
        const std::string path = "Contact pair " + p.name;
        Pair              pair;
        pair.parameters = &p;
        if (p.master_type == MasterType::surface)
          {
            require(Utilities::MPI::n_mpi_processes(comm) == 1,
                    "Contact pair '" + p.name +
                      "': deformable master surfaces ('" + p.master +
                      "') run on one process for now; run glide without "
                      "mpirun (or with -np 1), or use a rigid master.");
            std::set<types::boundary_id> master_ids;
            for (const auto &name : Utilities::split_string_list(p.master, ','))
              for (const auto id :
                   elasticity.get_mesh().surface(name, path + "/Master"))
                master_ids.insert(id);
            pair.surface = std::make_unique<MasterSurface<dim>>(elasticity,
                                                                master_ids,
                                                                p.smoothing,
                                                                path);
            require(!pair.surface->get_facets().empty(),
                    "Contact pair '" + p.name + "': the master surface '" +
                      p.master + "' has no faces.");
          }
        else
          pair.master = std::make_unique<RigidMaster<dim>>(p, path);

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
        double slave_modulus  = std::numeric_limits<double>::infinity();
        double master_modulus = std::numeric_limits<double>::infinity();
        if (p.master_type == MasterType::surface)
          for (const auto &name : Utilities::split_string_list(p.master, ','))
            for (unsigned int b = 0; b < scene.bodies.size(); ++b)
              if (name.rfind(scene.bodies[b].name + ".", 0) == 0)
                master_modulus = std::min(master_modulus,
                                          elasticity.youngs_modulus_of_body(b));
        std::map<types::global_dof_index, SlaveNode>    found;
        std::map<types::global_dof_index, unsigned int> n_facets;
        const bool                                      node_based =
          std::any_of(scene.node_sets.begin(),
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
                SlaveNode &node = found[dofs[0]];
                node.dofs       = dofs;
                node.X          = X;
                node.area       = 1.;
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
            // analysis) and the mean size of the adjacent slave facets. Ghost
            // cells contribute too, so that nodes on a process boundary get
            // their whole area.
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
                        SlaveNode &node = found[cell_dofs[k[0]]];
                        for (unsigned int c = 0; c < dim; ++c)
                          node.dofs[c] = cell_dofs[k[c]];
                        node.X = mapping.transform_unit_to_real_cell(
                          cell, unit_points[k[0]]);
                        for (unsigned int q = 0; q < quadrature.size(); ++q)
                          node.area += face_values.shape_value(k[0], q) *
                                       face_values.JxW(q) *
                                       (axisymmetric ?
                                          2 * numbers::PI *
                                            face_values.quadrature_point(q)[0] :
                                          1.);
                        node.size += cell->face(f)->diameter();
                        ++n_facets[cell_dofs[k[0]]];
                        // For surface to surface: the area-weighted normal
                        // and the surface mass int N_a N_b dA of the
                        // node's neighbours on the slave surface.
                        for (unsigned int q = 0; q < quadrature.size(); ++q)
                          {
                            const double dA =
                              face_values.JxW(q) *
                              (axisymmetric ?
                                 2 * numbers::PI *
                                   face_values.quadrature_point(q)[0] :
                                 1.);
                            node.normal += face_values.shape_value(k[0], q) *
                                           dA * face_values.normal_vector(q);
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
        pair.modulus  = std::min(slave_modulus, master_modulus);
        if (!std::isfinite(pair.modulus))
          pair.modulus = max_youngs_modulus;
        for (auto &[dof, node] : found)
          if (owned.is_element(dof))
            {
              node.size /= n_facets[dof];
              // A node-based slave scales c with its size^(dim-1), not with
              // its nominal area 1, so that iterations stay unit-free.
              node.c = pair.modulus *
                       (node_based ? std::pow(node.size, dim - 1) : node.area) /
                       node.size;
              const double stiffness = p.penalty_stiffness > 0 ?
                                         p.penalty_stiffness :
                                         1000. * pair.modulus / node.size;
              node.k                 = stiffness * node.area;
              pair.nodes.push_back(node);
            }
        const unsigned int n_global =
          Utilities::MPI::sum(static_cast<unsigned int>(pair.nodes.size()),
                              comm);
        require(n_global > 0,
                "Contact pair '" + p.name + "': the slave surface '" + p.slave +
                  "' has no nodes.");
        if (pair.surface)
          {
            std::set<types::global_dof_index> master_dofs;
            for (const auto &m : pair.surface->get_nodes())
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
            if (p.sliding != "small")
              for (const auto &node : pair.nodes)
                pair.previous_projection.push_back(
                  pair.surface->project(node.X, 1.5 * node.size));
            pair.coupled.resize(pair.nodes.size());
          }
        if (p.sliding == "small")
          setup_small_sliding(pair, path);
        for (const auto &node : pair.nodes)
          pair.previous_position.push_back(node.X);
        pair.slip.assign(pair.nodes.size(), 0.);
        pair.slip_components.assign(pair.nodes.size(), {{0., 0.}});
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
    release_holds();
  }

  template <int dim>
  void
  Contact<dim>::add_sparsity(DynamicSparsityPattern &dsp)
  {
    for (auto &pair : pairs)
      for (unsigned int i = 0; i < pair.nodes.size(); ++i)
        {
          const auto                          &node = pair.nodes[i];
          std::vector<types::global_dof_index> idx(node.dofs.begin(),
                                                   node.dofs.end());
          if (node.multiplier != numbers::invalid_dof_index)
            idx.push_back(node.multiplier);
          // Surface to surface: the averaging region.
          if (pair.small)
            for (const auto k : pair.anchors[i].region)
              for (unsigned int d = 0; d < dim; ++d)
                idx.push_back(pair.nodes[k].dofs[d]);
          if (pair.small && pair.surface)
            {
              // Small sliding: the fixed list of master nodes (R11.3).
              pair.coupled[i] = pair.anchors[i].list;
              for (const auto k : pair.coupled[i])
                for (unsigned int d = 0; d < dim; ++d)
                  idx.push_back(pair.surface->get_nodes()[k].dofs[d]);
            }
          else if (pair.surface)
            {
              // The master nodes within one facet size of the slave node's
              // current position (the surface is at the last iterate, see
              // needs_new_pattern()) ...
              Point<dim> x = node.X;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] = pair.surface->get_nodes().empty() ?
                         x[d] :
                         x[d] + current_displacement(node.dofs[d]);
              pair.coupled[i] =
                pair.surface->nodes_near(x, pair.surface->facet_size());
              // ... and those of its projection now (onto the piece it is
              // held on, if it is).
              const int held =
                i < pair.held_piece.size() ? pair.held_piece[i] : -1;
              const auto projection =
                held >= 0 ? pair.surface->project_onto(held, x) :
                            pair.surface->project(x, 1.5 * node.size);
              if (projection.found)
                {
                  const auto used = pair.surface->nodes_of(projection);
                  std::vector<unsigned int> all;
                  std::set_union(used.begin(),
                                 used.end(),
                                 pair.coupled[i].begin(),
                                 pair.coupled[i].end(),
                                 std::back_inserter(all));
                  pair.coupled[i] = all;
                }
              for (const auto k : pair.coupled[i])
                for (unsigned int d = 0; d < dim; ++d)
                  idx.push_back(pair.surface->get_nodes()[k].dofs[d]);
            }
          // Through the constraints: a slave node at a hanging node couples
          // with the DoFs it is constrained to.
          elasticity.update_constraints().add_entries_local_to_global(idx,
                                                                      dsp,
                                                                      false);
        }
  }

  template <int dim>
  bool
  Contact<dim>::needs_new_pattern(const VectorType &U)
  {
    bool outside = false;
    move_surfaces(U);
    for (const auto &pair : pairs)
      if (pair.surface && !pair.small)
        for (unsigned int i = 0; i < pair.nodes.size() && !outside; ++i)
          {
            const NodeState s = state(pair, pair.nodes[i], U);
            if (!s.found)
              continue;
            const auto used = pair.surface->nodes_of(s.projection);
            outside         = !std::includes(pair.coupled[i].begin(),
                                     pair.coupled[i].end(),
                                     used.begin(),
                                     used.end());
          }
    if (outside)
      {
        // Positions for add_sparsity().
        last_displacement = U;
      }
    return Utilities::MPI::max(outside ? 1 : 0, comm) > 0;
  }

  template <int dim>
  double
  Contact<dim>::current_displacement(const types::global_dof_index i) const
  {
    return last_displacement.size() > 0 ? last_displacement[i] : 0.;
  }

  template <int dim>
  void
  Contact<dim>::move_surfaces(const VectorType &U) const
  {
    const auto start = std::chrono::steady_clock::now();
    for (const auto &pair : pairs)
      if (pair.surface)
        pair.surface->set_displacement(U, !pair.small);
    if (std::any_of(pairs.begin(), pairs.end(), [](const Pair &p) {
          return !p.small;
        }))
      searching += std::chrono::steady_clock::now() - start;
  }

  template <int dim>
  std::vector<typename ActiveSetMonitor<dim>::Status>
  Contact<dim>::status(const VectorType &U) const
  {
    std::vector<typename ActiveSetMonitor<dim>::Status> result;
    move_surfaces(U);
    for (const auto &pair : pairs)
      for (const auto &node : pair.nodes)
        {
          const NodeState                        s = state(pair, node, U);
          typename ActiveSetMonitor<dim>::Status status;
          status.closed = s.closed;
          status.X      = node.X;
          if (pair.surface && !pair.small && s.found)
            {
              status.piece    = s.projection.piece;
              status.holdable = pair.parameters->smoothing == 0.;
            }
          result.push_back(status);
        }
    return result;
  }

  template <int dim>
  void
  Contact<dim>::hold(const std::vector<std::pair<unsigned int, int>> &holds)
  {
    for (const auto &[k, piece] : holds)
      {
        unsigned int first = 0;
        for (auto &pair : pairs)
          {
            if (k < first + pair.nodes.size())
              {
                if (pair.held_piece.size() != pair.nodes.size())
                  pair.held_piece.assign(pair.nodes.size(), -1);
                pair.held_piece[k - first] = piece;
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
      pair.held_piece.assign(pair.nodes.size(), -1);
  }

  template <int dim>
  void
  Contact<dim>::set_time(const double t)
  {
    time = t;
    for (auto &pair : pairs)
      if (pair.master)
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
    if (pair.small)
      {
        // Small sliding: the gap to the node's tangent plane; a node
        // without an anchor is never in contact (R7.4).
        const auto &a = pair.anchors[&node - pair.nodes.data()];
        s.found       = a.found;
        s.gap         = std::numeric_limits<double>::infinity();
        s.point       = s.x;
        if (a.sts)
          {
            // Surface to surface: the participation-weighted centre of the
            // averaging region.
            s.point = Point<dim>();
            for (unsigned int k = 0; k < a.region.size(); ++k)
              {
                const auto &other = pair.nodes[a.region[k]];
                for (unsigned int d = 0; d < dim; ++d)
                  s.point[d] +=
                    a.participation[k] * (other.X[d] + U[other.dofs[d]]);
              }
          }
        if (a.found && pair.surface)
          {
            const auto plane = pair.planes->plane(a, s.point);
            s.gap            = plane.gap;
            s.normal         = plane.normal;
            s.anchor         = plane.point;
            s.tangents       = plane.tangents;
          }
        else if (a.found)
          {
            // Analytical rigid master: the plane moves with it, and turns
            // with it unless sliding is infinitesimal.
            s.anchor   = pair.master->move(a.X0, 0., time);
            s.normal   = a.N0;
            s.tangents = contact_tangents<dim>(a.N0);
            if (scene.geometric_nonlinearity)
              {
                const auto turn = [&](const Tensor<1, dim> &v) {
                  const Tensor<1, dim> w =
                    pair.master->move(a.X0 + v, 0., time) - s.anchor;
                  return w / w.norm();
                };
                s.normal = turn(s.normal);
                for (auto &t : s.tangents)
                  t = turn(t);
              }
            s.gap = (s.point - s.anchor) * s.normal;
          }
      }
    else if (pair.surface)
      {
        const auto         start = std::chrono::steady_clock::now();
        const unsigned int i     = &node - pair.nodes.data();
        AssertIndexRange(i, pair.nodes.size());
        const int held = i < pair.held_piece.size() ? pair.held_piece[i] : -1;
        if (pair.cached.size() != pair.nodes.size())
          pair.cached.resize(pair.nodes.size());
        auto &c = pair.cached[i];
        if (c.version != pair.surface->version() || c.x != s.x ||
            c.held != held)
          {
            c.projection = held >= 0 ?
                             pair.surface->project_onto(held, s.x) :
                             pair.surface->project(s.x, 1.5 * node.size);
            c.version    = pair.surface->version();
            c.x          = s.x;
            c.held       = held;
          }
        s.projection = c.projection;
        searching += std::chrono::steady_clock::now() - start;
        s.found = s.projection.found;
        s.gap =
          s.found ? s.projection.gap : std::numeric_limits<double>::infinity();
        s.normal = s.projection.normal;
      }
    else
      {
        s.rigid  = pair.master->project(s.x);
        s.gap    = s.rigid.gap;
        s.normal = s.rigid.normal;
      }
    if (!pair.small)
      s.tangents = contact_tangents<dim>(s.normal);
    const double g = s.gap;
    if (node.multiplier != numbers::invalid_dof_index)
      {
        s.lambda = U[node.multiplier];
        // Active where lambda - c g >= 0: then C = c g (closed, g -> 0);
        // otherwise C = lambda (open, lambda -> 0).
        s.closed = s.found && s.lambda - node.c * (g - clearance) >= 0.;
      }
    else
      {
        s.lambda = s.found ? node.k * std::max(0., -g) : 0.;
        s.closed = s.found && g < 0.;
      }
    return s;
  }

  template <int dim>
  void
  Contact<dim>::linearize(const Pair                                 &pair,
                          const SlaveNode                            &node,
                          const NodeState                            &s,
                          const VectorType                           &U,
                          typename MasterSurface<dim>::Linearization &l) const
  {
    if (pair.small && pair.surface)
      {
        const auto &a = pair.anchors[&node - pair.nodes.data()];
        std::vector<
          std::pair<typename SmallSliding<dim>::SlaveDofs, Point<dim>>>
          slaves;
        if (a.sts)
          for (const auto k : a.region)
            {
              const auto &other = pair.nodes[k];
              Point<dim>  x     = other.X;
              for (unsigned int d = 0; d < dim; ++d)
                x[d] += U[other.dofs[d]];
              slaves.emplace_back(other.dofs, x);
            }
        else
          slaves.emplace_back(node.dofs, s.x);
        pair.planes->linearize(a, slaves, l);
        return;
      }
    if (pair.surface)
      {
        pair.surface->linearize(s.projection, s.x, node.dofs, l);
        return;
      }
    if (pair.small && pair.anchors[&node - pair.nodes.data()].sts)
      {
        // Surface to surface against a rigid master: g = (xbar - x0) . n
        // is linear in the region's displacements.
        const auto &a = pair.anchors[&node - pair.nodes.data()];
        l.dofs.clear();
        for (const auto k : a.region)
          l.dofs.insert(l.dofs.end(),
                        pair.nodes[k].dofs.begin(),
                        pair.nodes[k].dofs.end());
        const unsigned int n = l.dofs.size();
        l.gap                = s.gap;
        l.normal             = s.normal;
        l.dgap.reinit(n);
        l.force.reinit(n);
        l.dforce.reinit(n, n);
        for (unsigned int k = 0; k < a.region.size(); ++k)
          for (unsigned int d = 0; d < dim; ++d)
            l.dgap(dim * k + d) = l.force(dim * k + d) =
              a.participation[k] * s.normal[d];
        return;
      }
    // Rigid master: g depends on the slave node only; dg/du = n and the
    // force direction is n, with derivative d2g/du2 (curvature).
    l.dofs.assign(node.dofs.begin(), node.dofs.end());
    l.gap    = s.gap;
    l.normal = s.normal;
    l.dgap.reinit(dim);
    l.force.reinit(dim);
    l.dforce.reinit(dim, dim);
    for (unsigned int d = 0; d < dim; ++d)
      {
        l.dgap(d)  = s.normal[d];
        l.force(d) = s.normal[d];
        for (unsigned int e = 0; e < dim; ++e)
          l.dforce(d, e) = pair.small ? 0. : s.rigid.curvature[d][e];
      }
  }

  template <int dim>
  void
  Contact<dim>::assemble(const VectorType &U,
                         VectorType       *F,
                         MatrixType       *J) const
  {
    const auto &constraints = elasticity.update_constraints();
    std::string failure; // a projection that failed on this process
    move_surfaces(U);
    typename MasterSurface<dim>::Linearization l;
    Vector<double>                             rhs;
    FullMatrix<double>                         K;
    std::vector<types::global_dof_index>       idx;
    for (const auto &pair : pairs)
      {
        const bool hard = pair.parameters->enforcement == Enforcement::hard;
        const bool symmetrized = pair.parameters->symmetrized;
        for (unsigned int i = 0; i < pair.nodes.size(); ++i)
          {
            const auto &node = pair.nodes[i];
            NodeState   s;
            try
              {
                s = state(pair, node, U);
                if (s.found)
                  linearize(pair, node, s, U, l);
              }
            catch (const std::exception &e)
              {
                // Finish the loop so that every process reaches compress().
                failure = e.what();
                continue;
              }
            if (!s.found)
              {
                // Beyond the end of the master: open, lambda -> 0.
                if (!hard)
                  continue;
                idx.assign(1, node.multiplier);
                rhs.reinit(1);
                K.reinit(1, 1);
                rhs(0)  = s.lambda;
                K(0, 0) = 1.;
              }
            else
              {
                // Displacement rows: -lambda G, G the force direction (dg/du
                // where the normal is the gap's gradient); Jacobian
                // -lambda dG/du. Multiplier row: C(lambda, g).
                const unsigned int m = l.dofs.size();
                const unsigned int n = m + (hard ? 1 : 0);
                idx                  = l.dofs;
                rhs.reinit(n);
                K.reinit(n, n);
                for (unsigned int a = 0; a < m; ++a)
                  {
                    rhs(a) = -s.lambda * l.force(a);
                    for (unsigned int b = 0; b < m; ++b)
                      K(a, b) = -s.lambda * l.dforce(a, b);
                  }
                // The couplings between displacements and the constraint:
                // the force direction (column) and dg/du (row); their mean
                // when symmetrized (R5.2).
                Vector<double> column(l.force), row(l.dgap);
                if (symmetrized)
                  {
                    for (unsigned int a = 0; a < m; ++a)
                      for (unsigned int b = a + 1; b < m; ++b)
                        K(a, b) = K(b, a) = 0.5 * (K(a, b) + K(b, a));
                    column += l.dgap;
                    column *= 0.5;
                    row = column;
                  }
                if (hard)
                  {
                    idx.push_back(node.multiplier);
                    rhs(m) = s.closed ? node.c * (l.gap - clearance) : s.lambda;
                    for (unsigned int a = 0; a < m; ++a)
                      {
                        K(a, m) = -column(a);
                        K(m, a) = s.closed ? node.c * row(a) : 0.;
                      }
                    K(m, m) = s.closed ? 0. : 1.;
                  }
                else if (s.closed)
                  for (unsigned int a = 0; a < m; ++a)
                    for (unsigned int b = 0; b < m; ++b)
                      K(a, b) += node.k * column(a) * row(b);
                // Jacobian stabilization of open slave nodes near the
                // master (the residual is untouched, so the solution is
                // too): see stabilization_weight().
                const double w = stabilization_weight(pair, node, s);
                if (J && w > 0.)
                  for (unsigned int a = 0; a < m; ++a)
                    for (unsigned int b = 0; b < m; ++b)
                      K(a, b) += w * row(a) * row(b);
              }
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
  Contact<dim>::stabilization_weight(const Pair      &pair,
                                     const SlaveNode &node,
                                     const NodeState &s) const
  {
    // Not for faceted deformable masters (f = 0): there the gap gradient of
    // an open node jumps where its projection passes a vertex, and the
    // springs along it made the faceted Hertz scene (hertz-2d-elastic.prm
    // with f = 0) cut back 4 times where it needs none without them.
    if (pair.surface && !pair.small && pair.parameters->smoothing == 0.)
      return 0.;
    if (!stabilize || s.closed || !s.found || !(s.gap >= 0.) ||
        s.gap >= node.size)
      return 0.;
    const double w = 1. - s.gap / node.size;
    return stabilization * node.c * w * w;
  }

  template <int dim>
  void
  Contact<dim>::set_scaling(VectorType &residual_scale,
                            VectorType &solution_scale) const
  {
    // 1 / (E_min A_ref) times E_min / E_pair.
    for (const auto &pair : pairs)
      for (const auto &node : pair.nodes)
        if (node.multiplier != numbers::invalid_dof_index)
          {
            const double scale = elasticity.residual_scale() *
                                 elasticity.softest_youngs_modulus() /
                                 pair.modulus;
            residual_scale[node.multiplier] = scale;
            solution_scale[node.multiplier] = scale;
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
        // R16.3: what the contact computation could not do at this state,
        // counted per step: projections that failed to converge, nodes
        // beyond the end of the master (open by definition), nodes without
        // an anchor (small sliding), nodes held on one facet.
        unsigned int active = 0, failed = 0, beyond = 0, unanchored = 0,
                     held           = 0;
        double         normal_force = 0, penetration = 0;
        Tensor<1, dim> force;
        if (pair.surface)
          pair.surface->set_displacement(U, !pair.small);
        for (const auto &node : pair.nodes)
          {
            const NodeState s = state(pair, node, U);
            active += s.closed ? 1 : 0;
            if (pair.small)
              unanchored += s.found ? 0 : 1;
            else if (pair.surface && !s.found)
              {
                failed += s.projection.failed ? 1 : 0;
                beyond += s.projection.failed ? 0 : 1;
              }
            normal_force += s.lambda;
            force += s.lambda * s.normal;
            if (s.found)
              penetration = std::max(penetration, -s.gap);
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
        double max_slip = 0;
        for (const double slip : pair.slip)
          max_slip = std::max(max_slip, slip);
        row.emplace_back(p + "max_slip",
                         format_number(Utilities::MPI::max(max_slip, comm)));
        row.emplace_back(p + "max_penetration",
                         format_number(Utilities::MPI::max(penetration, comm)));
        for (const int i : pair.held_piece)
          held += i >= 0 ? 1 : 0;
        // Surface-to-surface constraints that fell back to node to surface
        // (R9.4; fixed at set-up, counted with every step).
        unsigned int fallbacks = 0;
        if (pair.small && pair.parameters->formulation == "surface to surface")
          for (const auto &a : pair.anchors)
            fallbacks += (a.found && !a.sts) ? 1 : 0;
        row.emplace_back(p + "projection_failed",
                         std::to_string(Utilities::MPI::sum(failed, comm)));
        row.emplace_back(p + "beyond_end",
                         std::to_string(Utilities::MPI::sum(beyond, comm)));
        row.emplace_back(p + "unanchored",
                         std::to_string(Utilities::MPI::sum(unanchored, comm)));
        row.emplace_back(p + "held",
                         std::to_string(Utilities::MPI::sum(held, comm)));
        row.emplace_back(p + "fallbacks",
                         std::to_string(Utilities::MPI::sum(fallbacks, comm)));
      }
    return row;
  }

  template <int dim>
  void
  Contact<dim>::update_slip(const VectorType &U,
                            const double      t_old,
                            const double      t_new)
  {
    move_surfaces(U);
    for (const auto &pair : pairs)
      {
        // R16.3: slave nodes whose closest-point projection failed to
        // converge are open at this state; name them.
        if (pair.surface && !pair.small)
          {
            std::vector<std::string> failed;
            for (const auto &node : pair.nodes)
              {
                const NodeState s = state(pair, node, U);
                if (!s.found && s.projection.failed)
                  {
                    std::ostringstream text;
                    text << "(" << node.X << ")";
                    failed.push_back(text.str());
                  }
              }
            report(failed,
                   "warning: contact pair '" + pair.parameters->name +
                     "': the projection onto the master did not converge for ",
                   " slave node(s), which count as open in this step (node "
                   "positions in the reference configuration)");
          }
        // How far the held gaps are from those of the free projection, and
        // the held nodes from the end of their piece.
        std::vector<std::string> held;
        double                   difference = 0., overshoot = 0.;
        for (unsigned int i = 0; i < pair.held_piece.size(); ++i)
          if (pair.held_piece[i] >= 0)
            {
              const auto     &node = pair.nodes[i];
              const NodeState s    = state(pair, node, U);
              const auto free = pair.surface->project(s.x, 1.5 * node.size);
              if (free.found)
                difference = std::max(difference, std::abs(free.gap - s.gap));
              // The distance along the piece's tangent plane from the end
              // of the piece to the node (0 inside the piece).
              Tensor<1, dim> r = s.x - s.projection.point;
              r -= (r * s.projection.normal) * s.projection.normal;
              const double past = s.projection.vertex ? r.norm() : 0.;
              overshoot         = std::max(overshoot, past);
              std::ostringstream text;
              text << "(" << node.X << ")";
              held.push_back(text.str());
            }
        difference = Utilities::MPI::max(difference, comm);
        overshoot  = Utilities::MPI::max(overshoot, comm);
        std::ostringstream after;
        after << " slave node(s) held on one master facet in this step (their "
                 "projection alternated between facets meeting at a corner; "
                 "the gap is measured to that facet's plane, at most "
              << difference << " from the free projection's, at most "
              << overshoot << " past the facet's end)";
        report(
          held, "contact pair '" + pair.parameters->name + "': ", after.str());
      }
    std::vector<std::vector<std::string>> slid_too_far(pairs.size());
    for (auto &pair : pairs)
      for (unsigned int i = 0; i < pair.nodes.size(); ++i)
        {
          const NodeState s = state(pair, pair.nodes[i], U);
          // The tangential part of the relative motion over the step: its
          // length adds to CSLIP, its components along the local tangent
          // directions (R13.1) to CSLIP1 (and CSLIP2).
          const auto accumulate = [&](const unsigned int    k,
                                      const Tensor<1, dim> &relative) {
            const Tensor<1, dim> &n = s.normal;
            pair.slip[k] += (relative - (relative * n) * n).norm();
            const auto tangents = contact_tangents<dim>(n);
            for (unsigned int a = 0; a < dim - 1; ++a)
              pair.slip_components[k][a] += relative * tangents[a];
          };
          if (pair.small)
            {
              // Small sliding: relative to the anchor's material point;
              // R12.2: warn once per node that moved along its plane
              // further than its limit from the anchor.
              // Slip is the change of the slave node's coordinates along
              // the plane's tangents, which turn with the master: a rigid
              // rotation of both bodies does not slip.
              if (!pair.anchors[i].found)
                continue;
              std::array<double, 2> offset{{0., 0.}};
              double                slide = 0.;
              for (unsigned int a = 0; a < dim - 1; ++a)
                {
                  offset[a] = (s.point - s.anchor) * s.tangents[a];
                  slide += offset[a] * offset[a];
                }
              slide = std::sqrt(slide);
              if (s.closed)
                {
                  double increment = 0.;
                  for (unsigned int a = 0; a < dim - 1; ++a)
                    {
                      const double d = offset[a] - pair.previous_offset[i][a];
                      pair.slip_components[i][a] += d;
                      increment += d * d;
                    }
                  pair.slip[i] += std::sqrt(increment);
                }
              pair.previous_offset[i] = offset;
              if (slide > pair.anchors[i].limit && !pair.warned[i])
                {
                  pair.warned[i] = true;
                  std::ostringstream x;
                  x << "(" << pair.nodes[i].X << ") slid " << slide << " > "
                    << pair.anchors[i].limit;
                  slid_too_far[&pair - pairs.data()].push_back(x.str());
                }
            }
          else if (s.closed && pair.surface)
            {
              // Relative to the master's material point that was under the
              // slave node at the end of the last step (same piece and
              // parameters, now in the current configuration).
              const auto &old = pair.previous_projection[i];
              if (old.found)
                {
                  const Point<dim> y =
                    pair.surface->evaluate(old.piece, old.xi).first;
                  const Point<dim> y_old = old.point;
                  accumulate(i,
                             (s.x - pair.previous_position[i]) - (y - y_old));
                }
            }
          else if (s.closed)
            {
              // The master point under the slave node at the start of the
              // step, moved with the master to the end of the step.
              pair.master->set_time(t_old);
              const Point<dim> y_old =
                pair.master->project(pair.previous_position[i]).closest_point;
              pair.master->set_time(t_new);
              const Point<dim> y_new = pair.master->move(y_old, t_old, t_new);
              accumulate(i,
                         (s.x - pair.previous_position[i]) - (y_new - y_old));
            }
          pair.previous_position[i] = s.x;
          if (pair.surface && !pair.small)
            pair.previous_projection[i] = s.projection;
        }
    for (unsigned int k = 0; k < pairs.size(); ++k)
      report(slid_too_far[k],
             "warning: contact pair '" + pairs[k].parameters->name +
               "': small sliding is not small for ",
             " slave node(s); they still load the master nodes of their "
             "anchor (R11.3); use finite sliding (node: slide from anchor > "
             "limit)");
  }

  template <int dim>
  void
  Contact<dim>::write_nodes(const VectorType  &U,
                            const std::string &directory,
                            const unsigned int step,
                            const double       time,
                            const bool         vtu)
  {
    // Per node: X (dim), x (dim), COPEN, force, CPRESS, CSTATUS, CSLIP,
    // normal (dim), local tangent directions ((dim - 1) x dim), slip
    // components CSLIP1 (, CSLIP2).
    const unsigned int n_values        = 3 * dim + 5 + (dim - 1) * (dim + 1);
    const unsigned int first_component = 3 * dim + 5 + (dim - 1) * dim;
    move_surfaces(U);
    for (auto &pair : pairs)
      {
        if (pair.master)
          pair.master->set_time(time);
        // The normal contact force on each slave node: its constraint's
        // force, or (surface to surface) the participation-weighted share
        // of the forces of every constraint whose region holds it.
        std::vector<NodeState> states;
        std::vector<double>    nodal(pair.nodes.size(), 0.);
        for (unsigned int i = 0; i < pair.nodes.size(); ++i)
          {
            states.push_back(state(pair, pair.nodes[i], U));
            const auto *a = pair.small ? &pair.anchors[i] : nullptr;
            if (a && a->sts)
              for (unsigned int k = 0; k < a->region.size(); ++k)
                nodal[a->region[k]] += a->participation[k] * states[i].lambda;
            else
              nodal[i] += states[i].lambda;
          }
        std::vector<double> local;
        for (unsigned int i = 0; i < pair.nodes.size(); ++i)
          {
            const auto      &node = pair.nodes[i];
            const NodeState &s    = states[i];
            for (unsigned int d = 0; d < dim; ++d)
              local.push_back(node.X[d]);
            for (unsigned int d = 0; d < dim; ++d)
              local.push_back(s.x[d]);
            local.push_back(s.gap);
            local.push_back(nodal[i]);
            local.push_back(nodal[i] / node.area);
            local.push_back(s.closed ? 1. : 0.);
            local.push_back(pair.slip[i]);
            for (unsigned int d = 0; d < dim; ++d)
              local.push_back(s.normal[d]);
            for (const auto &t : s.tangents)
              for (unsigned int d = 0; d < dim; ++d)
                local.push_back(t[d]);
            for (unsigned int a = 0; a < dim - 1; ++a)
              local.push_back(pair.slip_components[i][a]);
          }
        const auto all = Utilities::MPI::gather(comm, local, 0);
        if (Utilities::MPI::this_mpi_process(comm) != 0)
          continue;

        char number[16];
        std::snprintf(number, sizeof(number), "%04u", step);
        const std::string stem =
          directory + "/contact-" + pair.parameters->name;
        const char *X[] = {"X", "Y", "Z"}, *x[] = {"x", "y", "z"};

        // CSV: one row per slave node.
        {
          std::ofstream out(stem + "-" + number + ".csv.tmp");
          out.precision(12);
          for (unsigned int d = 0; d < dim; ++d)
            out << X[d] << ",";
          for (unsigned int d = 0; d < dim; ++d)
            out << x[d] << ",";
          out << "COPEN,force,CPRESS,CSTATUS,CSLIP";
          for (unsigned int a = 0; a < dim - 1; ++a)
            out << ",CSLIP" << a + 1;
          out << "\n";
          for (const auto &values : all)
            for (unsigned int k = 0; k + n_values <= values.size();
                 k += n_values)
              {
                for (unsigned int j = 0; j < 2 * dim + 5; ++j)
                  out << values[k + j] << (j + 1 < 2 * dim + 5 ? "," : "");
                for (unsigned int a = 0; a < dim - 1; ++a)
                  out << "," << values[k + first_component + a];
                out << "\n";
              }
        }
        std::rename((stem + "-" + number + ".csv.tmp").c_str(),
                    (stem + "-" + number + ".csv").c_str());

        if (!vtu)
          continue;
        // VTU: the slave nodes as points at their reference positions, with
        // the contact fields and the displacement (for Warp By Vector).
        std::vector<DataOutBase::Patch<0, dim>> patches;
        for (const auto &values : all)
          for (unsigned int k = 0; k + n_values <= values.size(); k += n_values)
            {
              DataOutBase::Patch<0, dim> patch;
              for (unsigned int d = 0; d < dim; ++d)
                patch.vertices[0][d] = values[k + d];
              patch.data.reinit(5 + 2 * dim + (dim - 1) * (dim + 1), 1);
              for (unsigned int j = 0; j < 5; ++j)
                patch.data(j, 0) = values[k + 2 * dim + j];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  patch.data(5 + d, 0) = values[k + 2 * dim + 5 + d];
                  patch.data(5 + dim + d, 0) =
                    values[k + dim + d] - values[k + d];
                }
              for (unsigned int j = 0; j < (dim - 1) * dim; ++j)
                patch.data(5 + 2 * dim + j, 0) = values[k + 3 * dim + 5 + j];
              for (unsigned int a = 0; a < dim - 1; ++a)
                patch.data(5 + 2 * dim + (dim - 1) * dim + a, 0) =
                  values[k + first_component + a];
              patch.patch_index = patches.size();
              patches.push_back(patch);
            }
        std::vector<std::string> names{
          "COPEN", "contact_force", "CPRESS", "CSTATUS", "CSLIP"};
        for (unsigned int d = 0; d < dim; ++d)
          names.push_back("contact_normal");
        for (unsigned int d = 0; d < dim; ++d)
          names.push_back("displacement");
        for (unsigned int a = 0; a < dim - 1; ++a)
          for (unsigned int d = 0; d < dim; ++d)
            names.push_back("tangent" + std::to_string(a + 1));
        for (unsigned int a = 0; a < dim - 1; ++a)
          names.push_back("CSLIP" + std::to_string(a + 1));
        std::vector<
          std::tuple<unsigned int,
                     unsigned int,
                     std::string,
                     DataComponentInterpretation::DataComponentInterpretation>>
          vectors{{5,
                   5 + dim - 1,
                   "contact_normal",
                   DataComponentInterpretation::component_is_part_of_vector},
                  {5 + dim,
                   5 + 2 * dim - 1,
                   "displacement",
                   DataComponentInterpretation::component_is_part_of_vector}};
        for (unsigned int a = 0; a < dim - 1; ++a)
          vectors.emplace_back(
            5 + 2 * dim + a * dim,
            5 + 2 * dim + a * dim + dim - 1,
            "tangent" + std::to_string(a + 1),
            DataComponentInterpretation::component_is_part_of_vector);
        const std::string file =
          "contact-" + pair.parameters->name + "-" + number + ".vtu";
        {
          std::ofstream out(directory + "/" + file + ".tmp");
          DataOutBase::write_vtu(
            patches, names, vectors, DataOutBase::VtkFlags(time), out);
        }
        std::rename((directory + "/" + file + ".tmp").c_str(),
                    (directory + "/" + file).c_str());
        pair.records.emplace_back(time, file);
        {
          std::ofstream out(stem + ".pvd.tmp");
          DataOutBase::write_pvd_record(out, pair.records);
        }
        std::rename((stem + ".pvd.tmp").c_str(), (stem + ".pvd").c_str());
      }
  }

  template <int dim>
  std::vector<std::string>
  Contact<dim>::active_effects() const
  {
    std::vector<std::string> e;
    for (const auto &pair : pairs)
      {
        const auto       &p = *pair.parameters;
        const std::string sliding =
          !pair.small ? "finite sliding" :
          scene.geometric_nonlinearity ?
                        "small sliding" :
                        "infinitesimal sliding (small sliding in a "
                        "geometrically linear scene: planes and load-transfer "
                        "weights fixed)";
        const std::string formulation = p.formulation == "surface to surface" ?
                                          "surface to surface, " :
                                          "node to surface, ";
        e.push_back("contact pair " + p.name + " (" + formulation + sliding +
                    ", " + p.master + ", " +
                    (p.enforcement == Enforcement::hard ? "hard" : "penalty") +
                    ", " +
                    std::to_string(Utilities::MPI::sum(
                      static_cast<unsigned int>(pair.nodes.size()), comm)) +
                    " slave nodes)");
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

  template <int dim>
  typename SmallSliding<dim>::Anchor
  Contact<dim>::rigid_anchor(const Pair &pair, const Point<dim> &X) const
  {
    typename SmallSliding<dim>::Anchor a;
    const auto                         projection = pair.master->project(X);
    a.found                                       = true;
    a.X0                                          = projection.closest_point;
    a.N0                                          = projection.normal;
    a.limit = std::numeric_limits<double>::infinity();
    return a;
  }

  template <int dim>
  typename SmallSliding<dim>::Anchor
  Contact<dim>::rigid_anchor_sts(
    const Pair                           &pair,
    const std::vector<Point<dim>>        &X,
    const std::vector<double>            &phi,
    const Tensor<1, dim>                 &slave_normal,
    const std::array<bool, dim>          &symmetric,
    typename SmallSliding<dim>::Fallback &reason) const
  {
    // An analytical master is smooth: each region node lands at its
    // closest point (where the master normal passes through it), and the
    // anchor is their weighted centre; otherwise as for a meshed master.
    typename SmallSliding<dim>::Anchor a;
    Point<dim>                         centre;
    const auto                         own = pair.master->project(X[0]);
    if (own.normal * slave_normal >= 0.)
      {
        reason = SmallSliding<dim>::Fallback::same_direction;
        return a;
      }
    for (unsigned int k = 0; k < X.size(); ++k)
      {
        a.X0 += phi[k] * pair.master->project(X[k]).closest_point;
        centre += phi[k] * X[k];
      }
    a.N0 = contact_direction<dim>(
      centre, a.X0, slave_normal, symmetric, 1e-8 * elasticity.length_scale());
    a.sts   = true;
    a.found = true;
    a.limit = std::numeric_limits<double>::infinity();
    reason  = SmallSliding<dim>::Fallback::none;
    return a;
  }

  template <int dim>
  void
  Contact<dim>::setup_surface_to_surface(Pair &pair)
  {
    const auto &p = *pair.parameters;
    require(Utilities::MPI::n_mpi_processes(comm) == 1,
            "Contact pair '" + p.name +
              "': 'Formulation = surface to surface' runs on one process for "
              "now (its averaging regions would be cut at process "
              "boundaries); run glide without mpirun (or with -np 1).");
    const bool node_based =
      std::any_of(scene.node_sets.begin(),
                  scene.node_sets.end(),
                  [&](const auto &n) { return n.name == p.slave; });
    // Slave DoFs on symmetry planes (R9.3).
    std::array<std::set<types::global_dof_index>, dim> symmetric;
    const auto &dof_handler = elasticity.get_dof_handler();
    std::vector<types::global_dof_index> cell_dofs(
      dof_handler.get_fe().n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            for (unsigned int c = 0; c < dim; ++c)
              for (const auto id : elasticity.symmetry_boundary_ids(c))
                if (id == cell->face(f)->boundary_id())
                  {
                    cell->get_dof_indices(cell_dofs);
                    for (const auto &[base, k] :
                         face_node_indices<dim>(dof_handler.get_fe(), cell, f))
                      symmetric[c].insert(cell_dofs[k[c]]);
                  }
    std::map<types::global_dof_index, unsigned int> index;
    for (unsigned int i = 0; i < pair.nodes.size(); ++i)
      index[pair.nodes[i].dofs[0]] = i;

    unsigned int n_node_based = 0, n_missed = 0, n_same = 0;
    for (unsigned int i = 0; i < pair.nodes.size(); ++i)
      {
        const auto &node = pair.nodes[i];
        const auto  nts  = [&]() {
          return pair.surface ? pair.planes->anchor(node.X) :
                                  rigid_anchor(pair, node.X);
        };
        if (node_based)
          {
            ++n_node_based;
            pair.anchors.push_back(nts());
            continue;
          }
        // The averaging region (R9.1): the node and its neighbours on the
        // slave surface, participation int N_i N_k dA / int N_i dA.
        std::vector<Point<dim>>   X{node.X};
        std::vector<unsigned int> region{i};
        std::vector<double>       phi{node.mass.at(node.dofs[0])};
        for (const auto &[dof, m] : node.mass)
          if (dof != node.dofs[0] && index.count(dof))
            {
              region.push_back(index[dof]);
              X.push_back(pair.nodes[index[dof]].X);
              phi.push_back(m);
            }
        double total = 0.;
        for (const double x : phi)
          total += x;
        for (auto &x : phi)
          x /= total;
        std::array<bool, dim> on_plane;
        for (unsigned int c = 0; c < dim; ++c)
          on_plane[c] = symmetric[c].count(node.dofs[c]) > 0;
        typename SmallSliding<dim>::Fallback reason;
        const Tensor<1, dim> slave_normal = node.normal / node.normal.norm();
        auto                 a =
          pair.surface ?
                            pair.planes->anchor_sts(X, phi, slave_normal, on_plane, reason) :
                            rigid_anchor_sts(pair, X, phi, slave_normal, on_plane, reason);
        if (a.found)
          {
            a.region        = region;
            a.participation = phi;
            pair.anchors.push_back(a);
            continue;
          }
        // R9.4: node to surface for this constraint.
        a = nts();
        if (reason == SmallSliding<dim>::Fallback::same_direction)
          ++n_same;
        else if (a.found)
          ++n_missed;
        pair.anchors.push_back(a);
      }
    n_node_based = Utilities::MPI::sum(n_node_based, comm);
    n_missed     = Utilities::MPI::sum(n_missed, comm);
    n_same       = Utilities::MPI::sum(n_same, comm);
    if (n_node_based + n_missed + n_same > 0 &&
        Utilities::MPI::this_mpi_process(comm) == 0)
      messages.push_back(
        "note: contact pair '" + p.name + "': surface to surface: " +
        std::to_string(n_node_based + n_missed + n_same) +
        " constraint(s) fall back to node to surface (R9.4): " +
        std::to_string(n_node_based) + " of a node-based slave surface, " +
        std::to_string(n_missed) +
        " where the projection along the slave normal misses the master, " +
        std::to_string(n_same) +
        " where slave and master normals point the same way");
  }

  template <int dim>
  void
  Contact<dim>::setup_small_sliding(Pair &pair, const std::string &path)
  {
    const auto &p = *pair.parameters;
    pair.small    = true;
    pair.warned.assign(pair.nodes.size(), false);
    if (pair.surface)
      {
        // User normals (R8.1): node sets -> master nodes.
        std::map<types::global_dof_index, unsigned int> master_node;
        const auto &master_nodes = pair.surface->get_nodes();
        for (unsigned int k = 0; k < master_nodes.size(); ++k)
          master_node[master_nodes[k].dofs[0]] = k;
        std::map<unsigned int, Tensor<1, dim>> user;
        for (const auto &[set, direction] : p.master_normals)
          {
            Tensor<1, dim> n;
            for (unsigned int d = 0; d < dim; ++d)
              n[d] = direction[d];
            unsigned int matched = 0;
            for (const auto &[dofs, X] :
                 elasticity.find_nodes(set, path + "/Master normals", false))
              {
                const auto it = master_node.find(dofs[0]);
                if (it == master_node.end())
                  continue;
                user[it->second] = n;
                ++matched;
              }
            require(Utilities::MPI::max(matched, comm) > 0,
                    "Parameter '" + path + "/Master normals': the node set '" +
                      set + "' has no node on the master surface '" + p.master +
                      "'.");
          }
        pair.planes =
          std::make_unique<SmallSliding<dim>>(*pair.surface,
                                              user,
                                              !scene.geometric_nonlinearity,
                                              scene.analysis ==
                                                AnalysisType::axisymmetric);
        // The only search of small sliding, once (counted as search time).
        const auto start = std::chrono::steady_clock::now();
        if (p.formulation == "surface to surface")
          setup_surface_to_surface(pair);
        else
          for (const auto &node : pair.nodes)
            pair.anchors.push_back(pair.planes->anchor(node.X));
        searching += std::chrono::steady_clock::now() - start;
      }
    else
      {
        // Analytical rigid master: the closest point and its normal at the
        // start.
        pair.master->set_time(0.);
        if (p.formulation == "surface to surface")
          setup_surface_to_surface(pair);
        else
          for (const auto &node : pair.nodes)
            pair.anchors.push_back(rigid_anchor(pair, node.X));
      }
    std::vector<std::string> unanchored;
    for (unsigned int i = 0; i < pair.nodes.size(); ++i)
      {
        pair.previous_offset.push_back({{0., 0.}});
        if (!pair.anchors[i].found)
          {
            std::ostringstream x;
            x << "(" << pair.nodes[i].X << ")";
            unanchored.push_back(x.str());
          }
      }
    report(unanchored,
           "note: contact pair '" + p.name + "': ",
           " slave node(s) found no anchor on the master (no master normal "
           "passes through them, R7.4); they are not constrained and may "
           "penetrate (check the master normals, 'Master normals', or "
           "symmetry conditions at the master's ends)");
  }

  template class Contact<2>;
  template class Contact<3>;
} // namespace glide
