#include <glide/base/collective_failure.h>
#include <glide/contact/small_sliding_formulation.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/mpi.h>

#include <sstream>

namespace glide
{
  using namespace dealii;

  template <int dim>
  SmallSlidingFormulation<dim>::SmallSlidingFormulation(
    const PairContext<dim>             &context,
    std::unique_ptr<RigidMaster<dim>>   master,
    std::unique_ptr<MasterSurface<dim>> surface,
    const bool                          surface_to_surface)
    : Formulation<dim>(context, std::move(master), std::move(surface))
    , surface_to_surface(surface_to_surface)
  {}

  template <int dim>
  void
  SmallSlidingFormulation<dim>::move(const VectorType &U) const
  {
    // Small sliding never searches (R6.2).
    if (this->surface)
      this->surface->set_displacement(U, false);
  }

  template <int dim>
  void
  SmallSlidingFormulation<dim>::setup(const std::vector<SlaveNode<dim>> &nodes)
  {
    Formulation<dim>::setup(nodes);
    const auto &p     = this->context.parameters;
    const auto &path  = this->context.path;
    const auto &scene = this->context.scene;
    const auto  comm  = this->context.comm;
    warned.assign(nodes.size(), false);
    anchors.clear();
    if (this->surface)
      {
        // User normals (R8.1): node sets -> master nodes.
        std::map<types::global_dof_index, unsigned int> master_node;
        const auto &master_nodes = this->surface->get_nodes();
        for (unsigned int k = 0; k < master_nodes.size(); ++k)
          master_node[master_nodes[k].dofs[0]] = k;
        std::map<unsigned int, Tensor<1, dim>> user;
        for (const auto &[set, direction] : p.master_normals)
          {
            Tensor<1, dim> n;
            for (unsigned int d = 0; d < dim; ++d)
              n[d] = direction[d];
            unsigned int matched = 0;
            for (const auto &[dofs, X] : this->context.elasticity.find_nodes(
                   set, path + "/Master normals", false))
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
        planes =
          std::make_unique<SmallSliding<dim>>(*this->surface,
                                              user,
                                              !scene.geometric_nonlinearity,
                                              scene.analysis ==
                                                AnalysisType::axisymmetric);
        throw_first_failure<InputError>(
          planes->inward_user_normal().empty() ?
            std::string() :
            "Parameter '" + path +
              "/Master normals': " + planes->inward_user_normal() +
              ". Give the normal that points out of the master, towards "
              "the slave.",
          comm);
        // The only search of small sliding, once (counted as search time).
        const auto start = std::chrono::steady_clock::now();
        if (surface_to_surface)
          setup_surface_to_surface();
        else
          for (const auto &node : nodes)
            anchors.push_back(planes->anchor(node.X));
        this->searching += std::chrono::steady_clock::now() - start;
      }
    else
      {
        // Analytical rigid master: the closest point and its normal at the
        // start.
        this->master->set_time(0.);
        // A slave node at the master's centre: misplaced (an input error on
        // every process).
        std::string failure;
        try
          {
            if (surface_to_surface)
              setup_surface_to_surface();
            else
              for (const auto &node : nodes)
                anchors.push_back(rigid_anchor(node.X, node.size));
          }
        catch (const UndefinedNormal &e)
          {
            failure = this->master->misplaced(e);
          }
        throw_first_failure<InputError>(failure, this->context.comm);
      }
    previous_offset.assign(nodes.size(), {{0., 0.}});
    std::vector<std::string> unanchored;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (!anchors[i].found)
        {
          std::ostringstream x;
          x << "(" << nodes[i].X << ")";
          unanchored.push_back(x.str());
        }
    this->context.report(
      unanchored,
      "note: contact pair '" + p.name + "': ",
      " slave node(s) found no anchor on the master (no master normal "
      "passes through them, R7.4); they are not constrained and may "
      "penetrate (check the master normals, 'Master normals', or "
      "symmetry conditions at the master's ends)");
  }

  template <int dim>
  Constraint<dim>
  SmallSlidingFormulation<dim>::evaluate(const unsigned int i,
                                         const VectorType  &U) const
  {
    Constraint<dim> s;
    s.x = this->position(i, U);
    // The gap to the node's tangent plane; a node without an anchor is
    // never in contact (R7.4).
    const auto &a = anchors[i];
    s.outcome     = a.found ? Outcome::found : Outcome::unanchored;
    s.gap         = std::numeric_limits<double>::infinity();
    s.point       = s.x;
    if (a.sts)
      {
        // Surface to surface: the participation-weighted centre of the
        // averaging region.
        s.point = Point<dim>();
        for (unsigned int k = 0; k < a.region.size(); ++k)
          {
            const Point<dim> x = region_position(a.region[k], U);
            for (unsigned int d = 0; d < dim; ++d)
              s.point[d] += a.participation[k] * x[d];
          }
      }
    if (a.found && this->surface)
      {
        const auto plane = planes->plane(a, s.point);
        s.gap            = plane.gap;
        s.normal         = plane.normal;
        s.anchor         = plane.point;
        s.tangents       = plane.tangents;
      }
    else if (a.found)
      {
        // Analytical rigid master: the plane moves with it, and turns with
        // it unless sliding is infinitesimal.
        s.anchor   = this->master->move(a.X0, 0., this->time);
        s.normal   = a.N0;
        s.tangents = contact_tangents<dim>(a.N0);
        if (this->context.scene.geometric_nonlinearity)
          {
            const auto turn = [&](const Tensor<1, dim> &v) {
              const Tensor<1, dim> w =
                this->master->move(a.X0 + v, 0., this->time) - s.anchor;
              return w / w.norm();
            };
            s.normal = turn(s.normal);
            for (auto &t : s.tangents)
              t = turn(t);
          }
        s.gap = (s.point - s.anchor) * s.normal;
      }
    return s;
  }

  template <int dim>
  void
  SmallSlidingFormulation<dim>::linearize(const unsigned int     i,
                                          const Constraint<dim> &s,
                                          const VectorType      &U,
                                          Linearization         &l) const
  {
    const auto &nodes = *this->nodes;
    const auto &node  = nodes[i];
    const auto &a     = anchors[i];
    if (this->surface)
      {
        std::vector<
          std::pair<typename SmallSliding<dim>::SlaveDofs, Point<dim>>>
          slaves;
        if (a.sts)
          for (const auto k : a.region)
            slaves.emplace_back(region_dofs(k), region_position(k, U));
        else
          slaves.emplace_back(node.dofs, s.x);
        planes->linearize(a, slaves, l);
        return;
      }
    // Analytical rigid master: g = (xbar - x0) . n is linear in the slave
    // displacements (the node, or the region of surface to surface).
    const std::vector<unsigned int> single{i};
    const auto                     &region = a.sts ? a.region : single;
    l.dofs.clear();
    for (const auto k : region)
      l.dofs.insert(l.dofs.end(), region_dofs(k).begin(), region_dofs(k).end());
    const unsigned int n = l.dofs.size();
    l.gap                = s.gap;
    l.normal             = s.normal;
    l.dgap.reinit(n);
    l.force.reinit(n);
    l.dforce.reinit(n, n);
    for (unsigned int k = 0; k < region.size(); ++k)
      for (unsigned int d = 0; d < dim; ++d)
        l.dgap(dim * k + d) = l.force(dim * k + d) =
          (a.sts ? a.participation[k] : 1.) * s.normal[d];
  }

  template <int dim>
  void
  SmallSlidingFormulation<dim>::couplings(
    const unsigned int i,
    const VectorType &,
    std::vector<types::global_dof_index> &dofs)
  {
    // Surface to surface: the averaging region.
    for (const auto k : anchors[i].region)
      for (unsigned int d = 0; d < dim; ++d)
        dofs.push_back(region_dofs(k)[d]);
    // The fixed list of master nodes (R11.3).
    if (this->surface)
      for (const auto k : anchors[i].list)
        for (unsigned int d = 0; d < dim; ++d)
          dofs.push_back(this->surface->get_nodes()[k].dofs[d]);
  }

  template <int dim>
  double
  SmallSlidingFormulation<dim>::own_gap(const unsigned int     i,
                                        const Constraint<dim> &s) const
  {
    const auto &a = anchors[i];
    if (!a.found || !a.sts || !s.found())
      return s.gap;
    if (this->surface)
      return planes->landing_gap(a, s.x, s.normal);
    // An analytical master: the node's own gap to it.
    try
      {
        return this->master->project(s.x).gap;
      }
    catch (const UndefinedNormal &)
      {
        return s.gap;
      }
  }

  template <int dim>
  unsigned int
  SmallSlidingFormulation<dim>::n_fallbacks() const
  {
    // Surface-to-surface constraints that fell back to node to surface
    // (R9.4; fixed at set-up).
    unsigned int n = 0;
    if (surface_to_surface)
      for (const auto &a : anchors)
        n += (a.found && !a.sts) ? 1 : 0;
    return n;
  }

  template <int dim>
  void
  SmallSlidingFormulation<dim>::distribute(
    const unsigned int                                       i,
    const double                                             lambda,
    std::vector<double>                                     &nodal,
    std::vector<std::pair<types::global_dof_index, double>> &elsewhere) const
  {
    // Surface to surface: the participation-weighted share of the forces
    // of every constraint whose region holds the node.
    const auto &a = anchors[i];
    if (!a.sts)
      {
        nodal[i] += lambda;
        return;
      }
    for (unsigned int k = 0; k < a.region.size(); ++k)
      if (a.region[k] < nodal.size())
        nodal[a.region[k]] += a.participation[k] * lambda;
      else
        elsewhere.emplace_back(region_dofs(a.region[k])[0],
                               a.participation[k] * lambda);
  }

  template <int dim>
  void
  SmallSlidingFormulation<dim>::read_dofs(
    std::vector<types::global_dof_index> &dofs) const
  {
    Formulation<dim>::read_dofs(dofs);
    for (const auto &n : neighbours)
      dofs.insert(dofs.end(), n.dofs.begin(), n.dofs.end());
  }

  template <int dim>
  const Point<dim> &
  SmallSlidingFormulation<dim>::region_X(const unsigned int k) const
  {
    const auto &nodes = *this->nodes;
    return k < nodes.size() ? nodes[k].X : neighbours[k - nodes.size()].X;
  }

  template <int dim>
  const std::array<types::global_dof_index, dim> &
  SmallSlidingFormulation<dim>::region_dofs(const unsigned int k) const
  {
    const auto &nodes = *this->nodes;
    return k < nodes.size() ? nodes[k].dofs : neighbours[k - nodes.size()].dofs;
  }

  template <int dim>
  Point<dim>
  SmallSlidingFormulation<dim>::region_position(const unsigned int k,
                                                const VectorType  &U) const
  {
    Point<dim> x = region_X(k);
    for (unsigned int d = 0; d < dim; ++d)
      x[d] += U[region_dofs(k)[d]];
    return x;
  }

  template <int dim>
  void
  SmallSlidingFormulation<dim>::commit_step(
    const VectorType &,
    const std::vector<Constraint<dim>> &s,
    const std::vector<bool>            &closed,
    const double,
    const double)
  {
    const auto              &nodes = *this->nodes;
    std::vector<std::string> slid_too_far;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        // Relative to the anchor's material point; slip is the change of
        // the slave point's coordinates along the plane's tangents, which
        // turn with the master: a rigid rotation of both bodies does not
        // slip. R12.2: warn once per node in or near contact that moved
        // along its plane further than its limit from the anchor.
        if (!anchors[i].found)
          continue;
        std::array<double, 2> offset{{0., 0.}};
        double                slide = 0.;
        for (unsigned int a = 0; a < dim - 1; ++a)
          {
            offset[a] = (s[i].point - s[i].anchor) * s[i].tangents[a];
            slide += offset[a] * offset[a];
          }
        slide = std::sqrt(slide);
        if (closed[i])
          {
            double increment = 0.;
            for (unsigned int a = 0; a < dim - 1; ++a)
              {
                const double d = offset[a] - previous_offset[i][a];
                this->slip_parts[i][a] += d;
                increment += d * d;
              }
            this->slip_length[i] += std::sqrt(increment);
          }
        previous_offset[i] = offset;
        // Closed nodes, and open ones within their facet size of the
        // plane (on a concave master, a hole, a node that slid reads as
        // open where it penetrates): an open node far from the contact
        // zone moves along its anchor's plane as the master moves past it,
        // and loads nothing.
        if ((closed[i] || s[i].gap < nodes[i].size) &&
            slide > anchors[i].limit && !warned[i])
          {
            warned[i] = true;
            std::ostringstream x;
            x << "(" << nodes[i].X << ") slid " << slide << " > "
              << anchors[i].limit;
            slid_too_far.push_back(x.str());
          }
      }
    this->context.report(
      slid_too_far,
      "warning: contact pair '" + this->context.parameters.name +
        "': small sliding is not small for ",
      " slave node(s); they still load the master nodes of their anchor "
      "(R11.3); use finite sliding (node: slide from anchor > limit)");
  }

  template <int dim>
  double
  SmallSlidingFormulation<dim>::sliding_limit(const double size) const
  {
    // R12.2 for an analytical master, as for a meshed one (one facet
    // length, less where the master turns by more than 10 degrees): the
    // slave node's facet size, less the slide over which a circle,
    // cylinder or sphere turns by 10 degrees, R pi / 18; a plane is its own
    // tangent plane. Until 2026-12-06 none was set, and a circle slid off
    // the block gave 35 times the force in silence. (rigid-punch.prm, f
    // = 0.0625: slid by 0.03, 0.06, 0.1 after a press of 0.05, the force
    // is 1.0, 3.8, 11.5 % above finite sliding's.)
    const double R = this->master->curvature_radius();
    if (std::isinf(R))
      return R;
    return size > 0. ? std::min(size, R * numbers::PI / 18.) :
                       R * numbers::PI / 18.;
  }

  template <int dim>
  typename SmallSliding<dim>::Anchor
  SmallSlidingFormulation<dim>::rigid_anchor(const Point<dim> &X,
                                             const double      size) const
  {
    typename SmallSliding<dim>::Anchor a;
    const auto                         projection = this->master->project(X);
    a.found                                       = true;
    a.X0                                          = projection.closest_point;
    a.N0                                          = projection.normal;
    a.limit                                       = sliding_limit(size);
    return a;
  }

  template <int dim>
  typename SmallSliding<dim>::Anchor
  SmallSlidingFormulation<dim>::rigid_anchor_sts(
    const std::vector<Point<dim>>        &X,
    const std::vector<double>            &phi,
    const Tensor<1, dim>                 &slave_normal,
    const std::array<bool, dim>          &symmetric,
    typename SmallSliding<dim>::Fallback &reason,
    const double                          size) const
  {
    // An analytical master is smooth: each region node lands at its
    // closest point (where the master normal passes through it), and the
    // anchor is their weighted centre; otherwise as for a meshed master.
    typename SmallSliding<dim>::Anchor a;
    Point<dim>                         centre;
    const auto                         own = this->master->project(X[0]);
    if (own.normal * slave_normal >= 0.)
      {
        reason = SmallSliding<dim>::Fallback::same_direction;
        return a;
      }
    for (unsigned int k = 0; k < X.size(); ++k)
      {
        a.X0 += phi[k] * this->master->project(X[k]).closest_point;
        centre += phi[k] * X[k];
      }
    a.N0 =
      contact_direction<dim>(centre,
                             a.X0,
                             slave_normal,
                             symmetric,
                             1e-8 * this->context.elasticity.length_scale());
    a.sts   = true;
    a.found = true;
    a.limit = sliding_limit(size);
    reason  = SmallSliding<dim>::Fallback::none;
    return a;
  }

  template <int dim>
  void
  SmallSlidingFormulation<dim>::setup_surface_to_surface()
  {
    const auto &p     = this->context.parameters;
    const auto &scene = this->context.scene;
    const auto  comm  = this->context.comm;
    const auto &nodes = *this->nodes;
    const bool  node_based =
      std::any_of(scene.node_sets.begin(),
                  scene.node_sets.end(),
                  [&](const auto &n) { return n.name == p.slave; });
    // Slave DoFs on symmetry planes (R9.3).
    std::array<std::set<types::global_dof_index>, dim> symmetric;
    const auto &dof_handler = this->context.elasticity.get_dof_handler();
    std::vector<types::global_dof_index> cell_dofs(
      dof_handler.get_fe().n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (!cell->is_artificial())
        for (const auto f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            for (unsigned int c = 0; c < dim; ++c)
              for (const auto id :
                   this->context.elasticity.symmetry_boundary_ids(c))
                if (id == cell->face(f)->boundary_id())
                  {
                    cell->get_dof_indices(cell_dofs);
                    for (const auto &[base, k] :
                         face_node_indices<dim>(dof_handler.get_fe(), cell, f))
                      symmetric[c].insert(cell_dofs[k[c]]);
                  }
    // Region nodes by x DoF: this process's slave nodes, then (under MPI)
    // those of other processes that lie in its regions. A region's nodes
    // share a facet with its node, so they lie within the largest facet
    // diameter of it, which is at most a node's mean facet size times its
    // number of facets (below the size of its mass row); each process
    // receives the slave nodes of the others within that reach (theirs) of
    // the boxes around its own nodes (R15.2: O(own part) per process, not the
    // whole slave surface), so that a region cut by the partition is the region
    // of the serial run.
    std::map<types::global_dof_index, unsigned int> index;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      index[nodes[i].dofs[0]] = i;
    std::map<types::global_dof_index, Neighbour> others;
    neighbours.clear();
    if (Utilities::MPI::n_mpi_processes(comm) > 1 && !node_based)
      {
        // Every process's boxes around its nodes (covering_boxes(), lower
        // and upper corners; none without slave nodes). Being a neighbour
        // is mutual, so the sender grows them by the reach of its own node.
        std::vector<Point<dim>> X;
        for (const auto &node : nodes)
          X.push_back(node.X);
        std::vector<double> flat;
        for (const auto &box : covering_boxes(X, 0.))
          for (const auto &corner : {box.get_boundary_points().first,
                                     box.get_boundary_points().second})
            for (unsigned int d = 0; d < dim; ++d)
              flat.push_back(corner[d]);
        const auto         boxes = Utilities::MPI::all_gather(comm, flat);
        const unsigned int me    = Utilities::MPI::this_mpi_process(comm);
        std::map<unsigned int, std::vector<double>> packed; // DoFs, then X
        for (unsigned int r = 0; r < boxes.size(); ++r)
          if (r != me)
            for (const auto &node : nodes)
              {
                const double reach  = node.size * node.mass.size();
                bool         inside = false;
                for (std::size_t k = 0;
                     k + 2 * dim <= boxes[r].size() && !inside;
                     k += 2 * dim)
                  {
                    inside = true;
                    for (unsigned int d = 0; d < dim && inside; ++d)
                      inside = boxes[r][k + d] - reach <= node.X[d] &&
                               node.X[d] <= boxes[r][k + dim + d] + reach;
                  }
                if (!inside)
                  continue;
                auto &part = packed[r];
                for (const auto d : node.dofs)
                  part.push_back(static_cast<double>(d)); // exact below 2^53
                for (unsigned int d = 0; d < dim; ++d)
                  part.push_back(node.X[d]);
              }
        for (const auto &[rank, part] :
             Utilities::MPI::some_to_some(comm, packed))
          for (std::size_t k = 0; k + 2 * dim <= part.size(); k += 2 * dim)
            {
              Neighbour n;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  n.dofs[d] = static_cast<types::global_dof_index>(part[k + d]);
                  n.X[d]    = part[k + dim + d];
                }
              if (index.count(n.dofs[0]) == 0)
                others[n.dofs[0]] = n;
            }
      }
    const auto region_index = [&](const types::global_dof_index dof) {
      if (const auto it = index.find(dof); it != index.end())
        return static_cast<int>(it->second);
      const auto it = others.find(dof);
      if (it == others.end())
        return -1;
      index[dof] = nodes.size() + neighbours.size();
      neighbours.push_back(it->second);
      return static_cast<int>(index[dof]);
    };

    unsigned int n_node_based = 0, n_missed = 0, n_same = 0;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        const auto &node = nodes[i];
        const auto  nts  = [&]() {
          return this->surface ? planes->anchor(node.X) :
                                   rigid_anchor(node.X, node.size);
        };
        if (node_based)
          {
            ++n_node_based;
            anchors.push_back(nts());
            continue;
          }
        // The averaging region (R9.1): the node and its neighbours on the
        // slave surface, participation int N_i N_k dA / int N_i dA.
        std::vector<Point<dim>>   X{node.X};
        std::vector<unsigned int> region{i};
        std::vector<double>       phi{node.mass.at(node.dofs[0])};
        for (const auto &[dof, m] : node.mass)
          if (const int k = region_index(dof); dof != node.dofs[0] && k >= 0)
            {
              region.push_back(k);
              X.push_back(region_X(k));
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
          this->surface ?
                            planes->anchor_sts(X, phi, slave_normal, on_plane, reason) :
                            rigid_anchor_sts(X, phi, slave_normal, on_plane, reason, node.size);
        if (a.found)
          {
            a.region        = region;
            a.participation = phi;
            anchors.push_back(a);
            continue;
          }
        // R9.4: node to surface for this constraint.
        a = nts();
        if (reason == SmallSliding<dim>::Fallback::same_direction)
          ++n_same;
        else if (a.found)
          ++n_missed;
        anchors.push_back(a);
      }
    // Under MPI: how many regions the partition cuts (their nodes of other
    // processes are read as ghosts, their forces sent to the owners).
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      {
        unsigned int n_cut = 0;
        for (const auto &a : anchors)
          n_cut += std::any_of(a.region.begin(),
                               a.region.end(),
                               [&](const unsigned int k) {
                                 return k >= nodes.size();
                               }) ?
                     1 :
                     0;
        n_cut                       = Utilities::MPI::sum(n_cut, comm);
        const unsigned int n_others = others.size();
        const unsigned int n_all =
          Utilities::MPI::sum(static_cast<unsigned int>(nodes.size()), comm);
        const unsigned int fewest = Utilities::MPI::min(n_others, comm),
                           most   = Utilities::MPI::max(n_others, comm);
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          this->context.note(
            "contact pair '" + p.name +
            "': surface to surface: " + std::to_string(n_cut) +
            " averaging region(s) hold slave nodes of another process; each "
            "process reads " +
            std::to_string(fewest) + " to " + std::to_string(most) +
            " of the " + std::to_string(n_all) +
            " slave nodes from the others");
      }
    n_node_based = Utilities::MPI::sum(n_node_based, comm);
    n_missed     = Utilities::MPI::sum(n_missed, comm);
    n_same       = Utilities::MPI::sum(n_same, comm);
    if (n_node_based + n_missed + n_same > 0 &&
        Utilities::MPI::this_mpi_process(comm) == 0)
      this->context.note(
        "note: contact pair '" + p.name + "': surface to surface: " +
        std::to_string(n_node_based + n_missed + n_same) +
        " constraint(s) fall back to node to surface (R9.4): " +
        std::to_string(n_node_based) + " of a node-based slave surface, " +
        std::to_string(n_missed) +
        " where the projection along the slave normal misses the master, " +
        std::to_string(n_same) +
        " where slave and master normals point the same way");
  }

  template class SmallSlidingFormulation<2>;
  template class SmallSlidingFormulation<3>;
} // namespace glide
