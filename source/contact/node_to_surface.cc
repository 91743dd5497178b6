#include <glide/contact/node_to_surface.h>
#include <glide/contact/small_sliding.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <iterator>
#include <sstream>

namespace glide
{
  using namespace dealii;

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::setup(const std::vector<SlaveNode<dim>> &nodes)
  {
    Formulation<dim>::setup(nodes);
    previous_position.clear();
    for (const auto &node : nodes)
      previous_position.push_back(node.X);
    if (this->surface)
      {
        // At the reference configuration (zero displacement).
        previous_point.clear();
        for (const auto &node : nodes)
          previous_point.push_back(
            material_point(this->surface->project(node.X, 1.5 * node.size),
                           VectorType()));
        coupled.assign(nodes.size(), {});
        cached.assign(nodes.size(), {});
      }
    release_holds();
  }

  template <int dim>
  Constraint<dim>
  NodeToSurfaceFinite<dim>::evaluate(const unsigned int i,
                                     const VectorType  &U) const
  {
    Constraint<dim> s;
    s.x     = this->position(i, U);
    s.point = s.x;
    if (this->surface)
      {
        const auto start = std::chrono::steady_clock::now();
        const int  held  = held_piece[i];
        auto      &c     = cached[i];
        if (c.version != this->surface->version() || c.x != s.x ||
            c.held != held || c.partner != held_partner[i])
          {
            c.projection = held_projection(i, s.x);
            c.version    = this->surface->version();
            c.x          = s.x;
            c.held       = held;
            c.partner    = held_partner[i];
          }
        s.projection = c.projection;
        this->searching += std::chrono::steady_clock::now() - start;
        s.outcome = s.projection.found  ? Outcome::found :
                    s.projection.failed ? Outcome::failed :
                                          Outcome::beyond_end;
        s.gap     = s.found() ? s.projection.gap :
                                std::numeric_limits<double>::infinity();
        s.normal  = s.projection.normal;
      }
    else
      {
        s.rigid  = this->master->project(s.x);
        s.gap    = s.rigid.gap;
        s.normal = s.rigid.normal;
      }
    s.tangents = contact_tangents<dim>(s.normal);
    return s;
  }

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::linearize(const unsigned int     i,
                                      const Constraint<dim> &s,
                                      const VectorType &,
                                      Linearization &l) const
  {
    const auto &node = (*this->nodes)[i];
    if (this->surface)
      {
        this->surface->linearize(s.projection, s.x, node.dofs, l);
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
          l.dforce(d, e) = s.rigid.curvature[d][e];
      }
  }

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::couplings(
    const unsigned int                    i,
    const VectorType                     &U,
    std::vector<types::global_dof_index> &dofs)
  {
    if (!this->surface)
      return;
    // The master nodes within one facet size of the slave node's position
    // at U (the surface must be at U) ...
    const auto &node = (*this->nodes)[i];
    Point<dim>  x    = node.X;
    if (U.size() > 0)
      x = this->position(i, U);
    coupled[i] = this->surface->nodes_near(x, this->surface->facet_size());
    const auto merge = [&](const std::vector<unsigned int> &more) {
      std::vector<unsigned int> all;
      std::set_union(more.begin(),
                     more.end(),
                     coupled[i].begin(),
                     coupled[i].end(),
                     std::back_inserter(all));
      coupled[i] = std::move(all);
    };
    // ... those of its projection now (onto the piece it is held on, if it
    // is), and those within one facet size of the projected point: a node
    // far from the master (the edge of a large slave surface) projects
    // more than a facet size away, and there its projection moves from
    // facet to facet as the master moves. Coupled only with the nodes
    // around itself, it left the pattern in every Newton iteration of the
    // 3D Hertz scene on a uniform block (8 rebuilds of the whole sparsity
    // pattern in 8 iterations at 2e5 DoFs).
    const auto projection = held_projection(i, x);
    if (projection.found)
      {
        merge(this->surface->nodes_of(projection));
        merge(this->surface->nodes_near(projection.point,
                                        this->surface->facet_size()));
      }
    for (const auto k : coupled[i])
      for (unsigned int d = 0; d < dim; ++d)
        dofs.push_back(this->surface->get_nodes()[k].dofs[d]);
  }

  template <int dim>
  bool
  NodeToSurfaceFinite<dim>::outside_pattern(const unsigned int     i,
                                            const Constraint<dim> &s) const
  {
    if (!this->surface || !s.found())
      return false;
    const auto used = this->surface->nodes_of(s.projection);
    return !std::includes(coupled[i].begin(),
                          coupled[i].end(),
                          used.begin(),
                          used.end());
  }

  template <int dim>
  int
  NodeToSurfaceFinite<dim>::holdable_piece(const Constraint<dim> &s) const
  {
    // Only faceted deformable masters have corners to alternate at.
    if (!this->surface || !s.found() ||
        this->context.parameters.smoothing != 0.)
      return -1;
    return static_cast<int>(this->surface->piece_key(s.projection.piece));
  }

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::hold(const unsigned int i,
                                 const int          piece,
                                 const int          partner)
  {
    AssertIndexRange(i, held_piece.size());
    // Keys (holdable_piece()) to the pieces held here.
    const int on = piece >= 0 && this->surface ?
                     this->surface->find_piece(static_cast<unsigned>(piece)) :
                     -1;
    const int with =
      partner >= 0 && this->surface ?
        this->surface->find_piece(static_cast<unsigned>(partner)) :
        -1;
    held_piece[i] = on;
    // At the vertex the two pieces share, where they are two faceted
    // linear facets of a 2D master: symmetric in the two, where holding on
    // either facet tilts the force by half the angle between them.
    held_partner[i] =
      on >= 0 && with >= 0 &&
          this->surface->project_at_vertex(on, with, (*this->nodes)[i].X)
            .found ?
        with :
        -1;
  }

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::renumber_pieces(
    const std::vector<std::uint64_t> &old_keys)
  {
    // A piece that is no longer held here (it left the reach of this
    // process's slave nodes) cannot be one a node is on.
    const auto renumber = [&](const int piece) {
      return piece >= 0 ? this->surface->find_piece(old_keys[piece]) : -1;
    };
    for (unsigned int i = 0; i < held_piece.size(); ++i)
      {
        held_piece[i]   = renumber(held_piece[i]);
        held_partner[i] = held_piece[i] >= 0 ? renumber(held_partner[i]) : -1;
      }
    // The cached projections refer to the old pieces: version() changed.
  }

  template <int dim>
  typename MasterSurface<dim>::Projection
  NodeToSurfaceFinite<dim>::held_projection(const unsigned int i,
                                            const Point<dim>  &x) const
  {
    const int held = held_piece[i];
    if (held < 0)
      return this->surface->project(x, 1.5 * (*this->nodes)[i].size);
    if (held_partner[i] >= 0)
      {
        const auto p =
          this->surface->project_at_vertex(held, held_partner[i], x);
        if (p.found)
          return p;
      }
    return this->surface->project_onto(held, x);
  }

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::release_holds()
  {
    // Vertex holds whose node was closed at its vertex at the end of the
    // last converged step (carried, commit_step()) go on into the next:
    // released, the node alternates again in every step.
    const unsigned int n = this->nodes ? this->nodes->size() : 0;
    if (held_piece.size() != n || carried.size() != n)
      {
        held_piece.assign(n, -1);
        held_partner.assign(n, -1);
        carried.assign(n, false);
        return;
      }
    for (unsigned int i = 0; i < n; ++i)
      if (!carried[i])
        {
          held_piece[i]   = -1;
          held_partner[i] = -1;
        }
  }

  template <int dim>
  unsigned int
  NodeToSurfaceFinite<dim>::n_held() const
  {
    return std::count_if(held_piece.begin(), held_piece.end(), [](int p) {
      return p >= 0;
    });
  }

  template <int dim>
  double
  NodeToSurfaceFinite<dim>::past_end(const Constraint<dim> &s)
  {
    Tensor<1, dim> r = s.x - s.projection.point;
    r -= (r * s.projection.normal) * s.projection.normal;
    return s.projection.vertex ? r.norm() : 0.;
  }

  template <int dim>
  std::vector<typename Formulation<dim>::HeldGap>
  NodeToSurfaceFinite<dim>::held_gaps(
    const std::vector<Constraint<dim>> &s) const
  {
    std::vector<typename Formulation<dim>::HeldGap> result;
    if (!this->surface)
      return result;
    const auto &x = this->surface->get_positions();
    for (unsigned int i = 0; i < held_piece.size(); ++i)
      if (held_piece[i] >= 0 && s[i].found())
        {
          const auto &nodes =
            this->surface
              ->get_facets()[this->surface->get_pieces()[held_piece[i]].facet]
              .nodes;
          const double length = x[nodes.front()].distance(x[nodes.back()]);
          const auto   free =
            this->surface->project(s[i].x, 1.5 * (*this->nodes)[i].size);
          // Beyond the end of the master: held in contact with nothing.
          result.push_back(
            {i, free.found ? std::abs(free.gap - s[i].gap) : length, length});
        }
    return result;
  }

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::commit_step(const VectorType                   &U,
                                        const std::vector<Constraint<dim>> &s,
                                        const std::vector<bool> &closed,
                                        const double             t_old,
                                        const double             t_new)
  {
    const auto &nodes = *this->nodes;
    const auto &p     = this->context.parameters;
    const auto  comm  = this->context.comm;
    if (this->surface)
      {
        // R16.3: slave nodes whose closest-point projection failed to
        // converge are open at this state; name them.
        this->report_failed(s, "the projection onto the master");
        // How far the held gaps are from those of the free projection, and
        // the held nodes from the end of their piece.
        std::vector<std::string> held;
        double                   difference = 0., overshoot = 0.;
        carried.assign(held_piece.size(), false);
        for (unsigned int i = 0; i < held_piece.size(); ++i)
          if (held_piece[i] >= 0)
            {
              const auto free =
                this->surface->project(s[i].x, 1.5 * nodes[i].size);
              if (free.found)
                difference =
                  std::max(difference, std::abs(free.gap - s[i].gap));
              // Closed at its vertex, where the held gap is the free one.
              carried[i] = held_partner[i] >= 0 && closed[i] && free.found &&
                           std::abs(free.gap - s[i].gap) <=
                             1e-8 * this->surface->facet_size();
              overshoot = std::max(overshoot, past_end(s[i]));
              std::ostringstream text;
              text << "(" << nodes[i].X << ")";
              held.push_back(text.str());
            }
        difference = Utilities::MPI::max(difference, comm);
        overshoot  = Utilities::MPI::max(overshoot, comm);
        std::ostringstream after;
        after << " slave node(s) held on one master facet in this step (their "
                 "projection alternated between facets meeting at a corner; "
                 "the gap is measured to that facet's plane, or, between "
                 "two facets of a 2D faceted master, along their mean "
                 "normal at the vertex they share; at most "
              << difference << " from the free projection's, at most "
              << overshoot << " past the facet's end)";
        this->context.report(
          held, "contact pair '" + p.name + "': ", after.str());
      }
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        if (closed[i] && this->surface)
          {
            // Relative to the master's material point that was under the
            // slave node at the end of the last step, moved with the
            // master's nodes. (Read from U: under MPI the piece it was on
            // may have left this process, and the step's slip was dropped
            // there until 2026-12-07; scene.slip_mpi_matches_serial.)
            if (!previous_point[i].empty())
              this->accumulate_slip(i,
                                    s[i].normal,
                                    (s[i].x - previous_position[i]) -
                                      previous_point[i].motion(U));
          }
        else if (closed[i])
          {
            // The master point under the slave node at the start of the
            // step, moved with the master to the end of the step.
            this->master->set_time(t_old);
            const Point<dim> y_old =
              this->master->project(previous_position[i]).closest_point;
            this->master->set_time(t_new);
            const Point<dim> y_new = this->master->move(y_old, t_old, t_new);
            this->accumulate_slip(i,
                                  s[i].normal,
                                  (s[i].x - previous_position[i]) -
                                    (y_new - y_old));
          }
        previous_position[i] = s[i].x;
        if (this->surface)
          previous_point[i] = material_point(s[i].projection, U);
      }
  }

  template <int dim>
  MaterialPoint<dim>
  NodeToSurfaceFinite<dim>::material_point(
    const typename MasterSurface<dim>::Projection &p,
    const VectorType                              &U) const
  {
    MaterialPoint<dim> point;
    if (p.found)
      {
        const auto weights = this->surface->point_weights(p.piece, p.xi);
        for (unsigned int d = 0; d < dim; ++d)
          for (const auto &[dof, w] : weights[d])
            point.add(d, dof, w, U);
      }
    return point;
  }

  template <int dim>
  void
  NodeToSurfaceFinite<dim>::read_dofs(
    std::vector<types::global_dof_index> &dofs) const
  {
    Formulation<dim>::read_dofs(dofs);
    for (const auto &point : previous_point)
      point.dofs(dofs);
  }

  template class NodeToSurfaceFinite<2>;
  template class NodeToSurfaceFinite<3>;
} // namespace glide
