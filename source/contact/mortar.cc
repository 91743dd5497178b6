#include <glide/base/collective_failure.h>
#include <glide/contact/facet_basis.h>
#include <glide/contact/mortar.h>
#include <glide/contact/mortar_geometry.h>
#include <glide/contact/small_sliding.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/quadrature_lib.h>

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

namespace glide
{
  using namespace dealii;

  namespace
  {
    using Fad = Sacado::Fad::DFad<double>;

    double
    plain(const double x)
    {
      return x;
    }
    double
    plain(const Fad &x)
    {
      return x.val();
    }

    template <typename T>
    T
    cross(const std::array<T, 2> &a, const std::array<T, 2> &b)
    {
      return a[0] * b[1] - a[1] * b[0];
    }

    /// Unit vector along @p a (a must not vanish).
    template <typename T, std::size_t n>
    std::array<T, n>
    unit(const std::array<T, n> &a)
    {
      using std::sqrt;
      T s = a[0] * a[0];
      for (std::size_t i = 1; i < n; ++i)
        s += a[i] * a[i];
      const T l = sqrt(s);
      auto    u = a;
      for (auto &x : u)
        x /= l;
      return u;
    }

    /// What solve_1d() found.
    enum class Root
    {
      found,        ///< a root (anywhere, not only in [0, 1])
      below,        ///< no root in [0, 1], and the equation's zero lies
                    ///< beyond s = 0: R(0) is the smaller in magnitude
      above,        ///< likewise beyond s = 1
      not_converged ///< a root in [0, 1] that neither Newton nor
                    ///< bisection found (non-finite values)
    };

    /**
     * Root of a scalar equation R(s) = 0 near @p start: Newton in double
     * to convergence, then one Newton step in T from the converged point,
     * which carries the exact first derivatives of the root (implicit
     * function theorem) when T is a Fad. @p f(s, R, dR) evaluates R and
     * R' at s for s of type double or T.
     *
     * Where Newton does not converge, the outcome is decided on [0, 1],
     * the facet's parameter range: a sign change of R there is bracketed
     * and bisected (then polished as above); without one, the line of the
     * projection misses the facet (a normal parallel to it, or a field of
     * normals that does not sweep over the point), which is geometry, not
     * a failure, and the side where the zero lies is the end with the
     * smaller |R| (exact for a flat facet with one normal, where R is
     * linear in s).
     */
    template <typename T, typename F>
    Root
    solve_1d(const F &f, const double start, T &root)
    {
      const auto polish = [&](const double s) {
        if constexpr (std::is_same_v<T, double>)
          root = s;
        else
          {
            T sT = s, RT, dRT;
            f(sT, RT, dRT);
            root = sT - RT / dRT;
          }
      };
      double s             = start;
      double previous_step = std::numeric_limits<double>::max();
      for (unsigned int it = 0; it < 30; ++it)
        {
          double R, dR;
          f(s, R, dR);
          if (!(std::abs(dR) > 0.) || !std::isfinite(R))
            break;
          const double step = R / dR;
          s -= step;
          if (!std::isfinite(s) || std::abs(s) > 1e3)
            break;
          // Converged, or at the round-off floor (mortar_geometry::
          // newton_stalled(): a short master facet far from the origin).
          if (std::abs(step) < 1e-14 * (1. + std::abs(s)) ||
              mortar_geometry::newton_stalled(std::abs(step), previous_step))
            {
              polish(s);
              return Root::found;
            }
          previous_step = std::abs(step);
        }
      double a = 0., b = 1., Ra, Rb, dR;
      f(a, Ra, dR);
      f(b, Rb, dR);
      if (!std::isfinite(Ra) || !std::isfinite(Rb))
        return Root::not_converged;
      if ((Ra > 0.) == (Rb > 0.) && Ra != 0. && Rb != 0.)
        return std::abs(Ra) < std::abs(Rb) ? Root::below : Root::above;
      for (unsigned int it = 0; it < 60 && b - a > 1e-15; ++it)
        {
          const double m = 0.5 * (a + b);
          double       Rm;
          f(m, Rm, dR);
          if (!std::isfinite(Rm))
            return Root::not_converged;
          if ((Rm > 0.) == (Ra > 0.) && Ra != 0.)
            {
              a  = m;
              Ra = Rm;
            }
          else
            b = m;
        }
      s = 0.5 * (a + b);
      f(s, Ra, dR);
      if (!(std::abs(dR) > 0.))
        return Root::not_converged;
      polish(s);
      return Root::found;
    }

    /// Position and tangent of a 2D facet of degree @p p with node
    /// positions @p X at parameter @p xi (and the shape values @p N).
    template <typename T, typename S>
    void
    line(const unsigned int                   p,
         const std::vector<std::array<T, 2>> &X,
         const S                             &xi,
         std::array<S, 3>                    &N,
         std::array<S, 2>                    &x,
         std::array<S, 2>                    &a)
    {
      std::array<S, 3> dN;
      lagrange(p, xi, N.data(), dN.data());
      for (unsigned int d = 0; d < 2; ++d)
        {
          x[d] = 0.;
          a[d] = 0.;
          for (unsigned int k = 0; k <= p; ++k)
            {
              x[d] += N[k] * X[k][d];
              a[d] += dN[k] * X[k][d];
            }
        }
    }


    /// Index of @p k in @p list (which holds it).
    unsigned int
    index_of(const std::vector<unsigned int> &list, const unsigned int k)
    {
      return std::find(list.begin(), list.end(), k) - list.begin();
    }
  } // namespace

  template <int dim>
  Mortar<dim>::Mortar(const PairContext<dim>             &context,
                      std::unique_ptr<MasterSurface<dim>> surface)
    : Formulation<dim>(context, nullptr, std::move(surface))
  {
    const auto &p = context.parameters;
    for (const auto &set : context.scene.node_sets)
      require(set.name != p.slave,
              "Parameter '" + context.path + "/Slave' = '" + p.slave +
                "' is a node set; mortar contact integrates over the slave "
                "surface and needs a surface <body>.<surface> (or use "
                "'Formulation = node to surface').");
    std::set<types::boundary_id> ids;
    for (const auto &name : Utilities::split_string_list(p.slave, ','))
      for (const auto id :
           context.elasticity.get_mesh().surface(name, context.path + "/Slave"))
        ids.insert(id);
    // The slave facets, extracted (and oriented outwards) as a master
    // surface is; no smoothing. Under MPI each process holds only the slave
    // facets around its own slave nodes (setup()).
    slave =
      std::make_unique<MasterSurface<dim>>(context.elasticity,
                                           ids,
                                           0.,
                                           context.path,
                                           Utilities::MPI::n_mpi_processes(
                                             context.comm) > 1);
  }

  template <int dim>
  void
  Mortar<dim>::setup(const std::vector<SlaveNode<dim>> &nodes)
  {
    Formulation<dim>::setup(nodes);
    if (Utilities::MPI::n_mpi_processes(this->context.comm) > 1)
      {
        // Distributed (R15.2, collective): the terms of node j need the
        // slave facets at j and, for the averaged normals of their nodes,
        // the facets at those nodes; all of them lie within one facet
        // size of j in the reference configuration, and the slave
        // surface's connectivity does not change, so one gather, with
        // twice that reach, serves the whole run.
        std::vector<Point<dim>> X;
        for (const auto &node : nodes)
          X.push_back(node.X);
        const double reach = 2. * slave->facet_size();
        slave->gather_near(VectorType(), covering_boxes(X, reach));
        const unsigned int held   = slave->get_facets().size();
        const auto         comm   = this->context.comm;
        const unsigned int fewest = Utilities::MPI::min(held, comm),
                           most   = Utilities::MPI::max(held, comm);
        std::ostringstream text;
        text << "contact pair '" << this->context.parameters.name
             << "': the slave surface's " << slave->n_facets_global()
             << " facets; each process holds those within " << reach
             << " of its slave nodes: " << fewest << " to " << most;
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          this->context.note(text.str());
      }
    const auto &surface_nodes = slave->get_nodes();
    std::map<types::global_dof_index, unsigned int> by_dof;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      by_dof[nodes[i].dofs[0]] = i;
    node_of.assign(surface_nodes.size(), numbers::invalid_unsigned_int);
    surface_node.assign(nodes.size(), numbers::invalid_unsigned_int);
    for (unsigned int k = 0; k < surface_nodes.size(); ++k)
      {
        const auto it = by_dof.find(surface_nodes[k].dofs[0]);
        if (it != by_dof.end())
          {
            node_of[k]               = it->second;
            surface_node[it->second] = k;
          }
      }
    for (unsigned int i = 0; i < nodes.size(); ++i)
      AssertThrow(surface_node[i] != numbers::invalid_unsigned_int,
                  ExcInternalError());
    std::map<types::global_dof_index, unsigned int> surface_node_of_dof;
    for (unsigned int k = 0; k < surface_nodes.size(); ++k)
      surface_node_of_dof[surface_nodes[k].dofs[0]] = k;
    // The hanging nodes merged into each slave node (their facets lie
    // within the gathered reach); a failure on one process is thrown on
    // all of them.
    members.assign(nodes.size(), {});
    std::string failure;
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        members[i].emplace_back(surface_node[i], 1.);
        for (const auto &[key, w] : nodes[i].hanging)
          {
            const auto it = surface_node_of_dof.find(key);
            if (it != surface_node_of_dof.end())
              members[i].emplace_back(it->second, w);
            else if (failure.empty())
              failure = "mortar (contact pair '" +
                        this->context.parameters.name +
                        "'): a hanging slave node merged into a slave node "
                        "is not on the part of the slave surface this "
                        "process holds";
          }
      }
    throw_first_failure<std::logic_error>(failure, this->context.comm);
    facets_at.assign(surface_nodes.size(), {});
    const auto &facets = slave->get_facets();
    for (unsigned int f = 0; f < facets.size(); ++f)
      for (const auto k : facets[f].nodes)
        facets_at[k].push_back(f);
    // Search radius per slave facet: 1.5 times its length in the
    // reference configuration (as node to surface searches around a slave
    // node): a master facet of any size whose box comes that close is a
    // candidate, and a penetration of up to that much is still found.
    radius.clear();
    for (const auto &facet : facets)
      radius.push_back(1.5 * surface_nodes[facet.nodes.front()].X.distance(
                               surface_nodes[facet.nodes.back()].X));
    coupled.assign(nodes.size(), {});
    previous_position.clear();
    for (const auto &node : nodes)
      previous_position.push_back(node.X);
    previous_point.assign(nodes.size(), {});
    previous_found.assign(nodes.size(), false);
    slave_x.clear();
  }

  template <int dim>
  void
  Mortar<dim>::read_dofs(std::vector<types::global_dof_index> &dofs) const
  {
    Formulation<dim>::read_dofs(dofs);
    for (const auto &node : slave->get_nodes())
      dofs.insert(dofs.end(), node.dofs.begin(), node.dofs.end());
    for (const auto &point : previous_point)
      point.dofs(dofs);
  }

  template <int dim>
  void
  Mortar<dim>::move(const VectorType &U) const
  {
    const auto start = std::chrono::steady_clock::now();
    this->surface->set_displacement(U, false);
    slave->set_displacement(U, false);
    slave_x = slave->get_positions();
    if (tree_version != this->surface->version())
      {
        // The master facets' bounding boxes at the current positions.
        const auto       &x = this->surface->get_positions();
        std::vector<Leaf> boxes;
        const auto       &facets = this->surface->get_facets();
        for (unsigned int f = 0; f < facets.size(); ++f)
          {
            Point<dim> lo = x[facets[f].nodes[0]], hi = lo;
            for (const auto k : facets[f].nodes)
              for (unsigned int d = 0; d < dim; ++d)
                {
                  lo[d] = std::min(lo[d], x[k][d]);
                  hi[d] = std::max(hi[d], x[k][d]);
                }
            boxes.emplace_back(BoundingBox<dim>(std::make_pair(lo, hi)), f);
          }
        tree         = pack_rtree(boxes);
        tree_version = this->surface->version();
      }
    this->searching += std::chrono::steady_clock::now() - start;
  }

  template <int dim>
  std::vector<unsigned int>
  Mortar<dim>::candidates(const unsigned int facet, const double r) const
  {
    namespace bgi     = boost::geometry::index;
    const auto &nodes = slave->get_facets()[facet].nodes;
    Point<dim>  lo = slave_x[nodes[0]], hi = lo;
    for (const auto k : nodes)
      for (unsigned int d = 0; d < dim; ++d)
        {
          lo[d] = std::min(lo[d], slave_x[k][d] - r);
          hi[d] = std::max(hi[d], slave_x[k][d] + r);
        }
    std::vector<Leaf> found;
    tree.query(bgi::intersects(BoundingBox<dim>(std::make_pair(lo, hi))),
               std::back_inserter(found));
    std::vector<unsigned int> result;
    for (const auto &leaf : found)
      result.push_back(leaf.second);
    std::sort(result.begin(), result.end());
    return result;
  }

  template <int dim>
  template <typename T>
  void
  Mortar<dim>::add_weighted(const Terms<T> &t,
                            const double    w,
                            const bool      first,
                            Terms<T>       &sum) const
  {
    if (first)
      sum.normal = t.normal;
    sum.weight += w * t.weight;
    sum.weighted_gap += w * t.weighted_gap;
    sum.failed = sum.failed || t.failed;
    for (unsigned int a = 0; a < t.master_nodes.size(); ++a)
      sum.M[index_of(sum.master_nodes, t.master_nodes[a])] += w * t.M[a];
  }

  template <int dim>
  std::vector<typename Mortar<dim>::Patch>
  Mortar<dim>::patches(const unsigned int i) const
  {
    std::vector<Patch> result;
    for (const auto &member : members[i])
      result.push_back(patch_at(member.first));
    return result;
  }

  template <int dim>
  typename Mortar<dim>::Patch
  Mortar<dim>::patch_at(const unsigned int j) const
  {
    Patch      p;
    const auto add = [](std::vector<unsigned int> &list, const unsigned int k) {
      if (std::find(list.begin(), list.end(), k) == list.end())
        list.push_back(k);
    };
    const auto &facets = slave->get_facets();
    p.slave.push_back(j);
    p.facets = facets_at[j];
    // The facets at j, and (for the nodal normals of their nodes) the
    // facets at those nodes.
    for (const auto f : p.facets)
      for (const auto k : facets[f].nodes)
        for (const auto g : facets_at[k])
          for (const auto m : facets[g].nodes)
            add(p.slave, m);
    std::vector<unsigned int> master;
    for (const auto f : p.facets)
      {
        p.candidates.push_back(candidates(f, radius[f]));
        // 3D: only the candidates that overlap the slave facet (so that
        // the linearization differentiates with respect to their nodes
        // only; the others contribute nothing).
        if constexpr (dim == 3)
          {
            auto &c = p.candidates.back();
            c.erase(std::remove_if(c.begin(),
                                   c.end(),
                                   [&](const unsigned int m) {
                                     return !overlaps_3d(f, m);
                                   }),
                    c.end());
          }
        for (const auto c : p.candidates.back())
          for (const auto m : this->surface->get_facets()[c].nodes)
            master.push_back(m);
      }
    std::sort(master.begin(), master.end());
    master.erase(std::unique(master.begin(), master.end()), master.end());
    p.master = master;
    return p;
  }

  template <int dim>
  template <typename T>
  void
  Mortar<dim>::compute(const Patch                           &p,
                       const std::vector<std::array<T, dim>> &xs,
                       const std::vector<std::array<T, dim>> &xm,
                       Terms<T>                              &t) const
  {
    t.master_nodes = p.master;
    t.M.assign(p.master.size(), T(0.));
    if constexpr (dim == 3)
      compute_3d(p, xs, xm, t);
    else
      {
        using V                      = std::array<T, 2>;
        const auto        &s_facets  = slave->get_facets();
        const auto        &m_facets  = this->surface->get_facets();
        const auto        &symmetric = slave->get_symmetry_flags();
        const unsigned int ps = slave->degree(), pm = this->surface->degree();
        const bool         axisymmetric =
          this->context.scene.analysis == AnalysisType::axisymmetric;
        const auto facet_positions = [&](const unsigned int f) {
          std::vector<V> X;
          for (const auto k : s_facets[f].nodes)
            X.push_back(xs[index_of(p.slave, k)]);
          return X;
        };
        // Outward unit normal (a_y, -a_x)/|a| of slave facet f at its
        // parameter xi.
        const auto facet_normal = [&](const unsigned int f, const double xi) {
          std::array<T, 3> N;
          V                x, a;
          line<T, T>(ps, facet_positions(f), T(xi), N, x, a);
          return unit<T, 2>(V{{a[1], -a[0]}});
        };
        // Nodal normal: mean of the unit normals of the facets at the node
        // (at a mid-side node: its facet's); at the end of the slave
        // surface on a symmetry plane (or the axis), projected into the
        // plane, as the mirror image of the end facet would make it.
        const auto nodal_normal = [&](const unsigned int k) {
          V n{{T(0.), T(0.)}};
          for (const auto f : facets_at[k])
            {
              const unsigned int local = index_of(s_facets[f].nodes, k);
              const auto         m     = facet_normal(f, double(local) / ps);
              n[0] += m[0];
              n[1] += m[1];
            }
          bool end = facets_at[k].size() == 1 &&
                     (index_of(s_facets[facets_at[k][0]].nodes, k) == 0 ||
                      index_of(s_facets[facets_at[k][0]].nodes, k) == ps);
          if (end)
            for (unsigned int c = 0; c < 2; ++c)
              if (symmetric[k][c] || (c == 0 && axisymmetric &&
                                      std::abs(slave->get_nodes()[k].X[0]) <
                                        1e-10 * slave->facet_size()))
                n[c] = 0.;
          return unit<T, 2>(n);
        };
        t.normal = nodal_normal(p.slave[0]);

        const QGauss<1> gauss(5);
        struct Point_
        {
          std::array<T, 3> N, Nm;
          T                wJ, gap;
          unsigned int     master_facet;
        };
        for (const unsigned int f : p.facets)
          {
            const auto     X = facet_positions(f);
            std::vector<V> n;
            for (const auto k : s_facets[f].nodes)
              n.push_back(nodal_normal(k));
            // Slave point and (unnormalized) normal field at xi.
            const auto field = [&](const auto &xi,
                                   auto       &N,
                                   auto       &x,
                                   auto       &a,
                                   auto       &nn,
                                   auto       &dnn) {
              using S = std::decay_t<decltype(xi)>;
              std::array<S, 3> dN;
              lagrange(ps, xi, N.data(), dN.data());
              for (unsigned int d = 0; d < 2; ++d)
                {
                  x[d] = a[d] = nn[d] = dnn[d] = 0.;
                  for (unsigned int k = 0; k <= ps; ++k)
                    {
                      if constexpr (std::is_same_v<S, double>)
                        {
                          x[d] += N[k] * plain(X[k][d]);
                          a[d] += dN[k] * plain(X[k][d]);
                          nn[d] += N[k] * plain(n[k][d]);
                          dnn[d] += dN[k] * plain(n[k][d]);
                        }
                      else
                        {
                          x[d] += N[k] * X[k][d];
                          a[d] += dN[k] * X[k][d];
                          nn[d] += N[k] * n[k][d];
                          dnn[d] += dN[k] * n[k][d];
                        }
                    }
                }
            };
            // The slave parameter xi whose normal line passes through y:
            // (y - x(xi)) x n(xi) = 0.
            const auto onto_slave = [&](const V &y, T &xi) {
              const auto f = [&](const auto &s, auto &R, auto &dR) {
                using S = std::decay_t<decltype(s)>;
                std::array<S, 3> N;
                std::array<S, 2> x, a, nn, dnn, r;
                field(s, N, x, a, nn, dnn);
                for (unsigned int d = 0; d < 2; ++d)
                  {
                    if constexpr (std::is_same_v<S, double>)
                      r[d] = plain(y[d]) - x[d];
                    else
                      r[d] = y[d] - x[d];
                  }
                R = cross(r, nn);
                dR =
                  cross(std::array<S, 2>{{-a[0], -a[1]}}, nn) + cross(r, dnn);
              };
              // Start: the projection onto the chord.
              const double c0 = plain(X[0][0]), c1 = plain(X[0][1]);
              const double e0 = plain(X[ps][0]) - c0, e1 = plain(X[ps][1]) - c1;
              const double start =
                ((plain(y[0]) - c0) * e0 + (plain(y[1]) - c1) * e1) /
                (e0 * e0 + e1 * e1);
              return solve_1d<T>(f, start, xi);
            };
            // The master parameter whose point lies on the slave normal
            // line at slave parameter xi (in double, for decisions only).
            const auto master_at =
              [&](const std::vector<std::array<double, 2>> &Yd,
                  const double                              xi,
                  double                                   &eta) {
                std::array<double, 3> N;
                std::array<double, 2> x, a, nn, dnn;
                field(xi, N, x, a, nn, dnn);
                const auto h = [&](const double s, double &R, double &dR) {
                  std::array<double, 3> Nm;
                  std::array<double, 2> y, b;
                  line<double, double>(pm, Yd, s, Nm, y, b);
                  R  = cross(std::array<double, 2>{{y[0] - x[0], y[1] - x[1]}},
                            nn);
                  dR = cross(b, nn);
                };
                return solve_1d<double>(h, 0.5, eta);
              };
            const double        mid_normal[2] = {plain(facet_normal(f, 0.5)[0]),
                                                 plain(facet_normal(f, 0.5)[1])};
            std::vector<Point_> points;
            for (const unsigned int c : p.candidates[index_of(p.facets, f)])
              {
                std::vector<V> Y;
                for (const auto m : m_facets[c].nodes)
                  Y.push_back(xm[index_of(p.master, m)]);
                std::vector<std::array<double, 2>> Yd;
                for (const auto &v : Y)
                  Yd.push_back({{plain(v[0]), plain(v[1])}});
                // Only master facets that face the slave facet.
                {
                  std::array<double, 3> N;
                  std::array<double, 2> y, b;
                  line<double, double>(pm, Yd, 0.5, N, y, b);
                  if (b[1] * mid_normal[0] - b[0] * mid_normal[1] >= 0.)
                    continue;
                }
                // The segment: the master facet's ends projected onto the
                // slave facet along the slave normal field, cut to [0, 1].
                T          xa = 0., xb = 0.;
                const Root ra = onto_slave(Y[0], xa);
                const Root rb = onto_slave(Y[pm], xb);
                if (ra == Root::not_converged || rb == Root::not_converged)
                  {
                    t.failed = true;
                    continue;
                  }
                T lo = 0., hi = 0.;
                if (ra == Root::found && rb == Root::found)
                  {
                    using std::max;
                    using std::min;
                    lo = max(min(xa, xb), T(0.));
                    hi = min(max(xa, xb), T(1.));
                  }
                else
                  {
                    // A master end whose normal line misses the slave facet
                    // (the slave normals turn fast, or run parallel to the
                    // master): the segment is where the slave normal lines
                    // hit the master facet. [0, 1] is cut at the end
                    // projection that exists (if any, and inside), and each
                    // piece is kept if the normal line at its middle hits
                    // the master facet; with at most two pieces, those kept
                    // are adjacent.
                    std::vector<T> cuts{T(0.)};
                    for (const auto &[r, x] :
                         {std::make_pair(ra, &xa), std::make_pair(rb, &xb)})
                      if (r == Root::found && plain(*x) > 0. && plain(*x) < 1.)
                        cuts.push_back(*x);
                    cuts.push_back(T(1.));
                    int first = -1, last = -1;
                    for (unsigned int k = 0; k + 1 < cuts.size(); ++k)
                      {
                        double     eta;
                        const Root r =
                          master_at(Yd,
                                    0.5 * (plain(cuts[k]) + plain(cuts[k + 1])),
                                    eta);
                        if (r == Root::found && eta >= 0. && eta <= 1.)
                          {
                            if (first < 0)
                              first = k;
                            last = k;
                          }
                      }
                    if (first < 0)
                      continue;
                    lo = cuts[first];
                    hi = cuts[last + 1];
                  }
                if (!(plain(hi) - plain(lo) > 1e-12))
                  continue;
                for (unsigned int g = 0; g < gauss.size(); ++g)
                  {
                    Point_  q;
                    const T xi = lo + (hi - lo) * gauss.point(g)[0];
                    V       x, a, nn, dnn;
                    field(xi, q.N, x, a, nn, dnn);
                    nn = unit<T, 2>(nn);
                    using std::sqrt;
                    q.wJ = (hi - lo) * gauss.weight(g) *
                           sqrt(a[0] * a[0] + a[1] * a[1]);
                    if (axisymmetric)
                      q.wJ *= 2. * numbers::PI * x[0];
                    // The master point on the line through x along n:
                    // (y(eta) - x) x n = 0.
                    const auto h = [&](const auto &s, auto &R, auto &dR) {
                      using S = std::decay_t<decltype(s)>;
                      std::array<S, 3> N;
                      std::array<S, 2> y, b, r, m;
                      if constexpr (std::is_same_v<S, double>)
                        {
                          std::vector<std::array<double, 2>> Yd;
                          for (const auto &v : Y)
                            Yd.push_back({{plain(v[0]), plain(v[1])}});
                          line<double, double>(pm, Yd, s, N, y, b);
                          for (unsigned int d = 0; d < 2; ++d)
                            {
                              r[d] = y[d] - plain(x[d]);
                              m[d] = plain(nn[d]);
                            }
                        }
                      else
                        {
                          line<T, T>(pm, Y, s, N, y, b);
                          for (unsigned int d = 0; d < 2; ++d)
                            {
                              r[d] = y[d] - x[d];
                              m[d] = nn[d];
                            }
                        }
                      R  = cross(r, m);
                      dR = cross(b, m);
                    };
                    // A slave normal that misses the master facet (parallel
                    // to it, or through neither of its ends' sides): no
                    // partner on this facet.
                    T          eta;
                    const Root found = solve_1d<T>(h, 0.5, eta);
                    if (found == Root::not_converged)
                      t.failed = true;
                    if (found != Root::found)
                      continue;
                    V y, b;
                    line<T, T>(pm, Y, eta, q.Nm, y, b);
                    q.gap = (y[0] - x[0]) * nn[0] + (y[1] - x[1]) * nn[1];
                    q.master_facet = c;
                    points.push_back(q);
                  }
              }
            if (points.empty())
              continue;
            // The dual basis on the covered part: A = D M^{-1}.
            const unsigned int          n_s = ps + 1;
            std::vector<T>              D(n_s, T(0.));
            std::vector<std::vector<T>> M(n_s, std::vector<T>(n_s, T(0.)));
            T                           covered = 0.;
            for (const auto &q : points)
              {
                covered += q.wJ;
                for (unsigned int k = 0; k < n_s; ++k)
                  {
                    D[k] += q.N[k] * q.wJ;
                    for (unsigned int l = 0; l < n_s; ++l)
                      M[k][l] += q.N[k] * q.N[l] * q.wJ;
                  }
              }
            if (!mortar_geometry::invert_small(M))
              continue;
            const unsigned int kj = index_of(s_facets[f].nodes, p.slave[0]);
            std::vector<T>     A(n_s);
            for (unsigned int l = 0; l < n_s; ++l)
              A[l] = D[kj] * M[kj][l];
            for (const auto &q : points)
              {
                T phi = 0.;
                for (unsigned int l = 0; l < n_s; ++l)
                  phi += A[l] * q.N[l];
                t.weighted_gap += phi * q.gap * q.wJ;
                const auto &mn = m_facets[q.master_facet].nodes;
                for (unsigned int l = 0; l <= pm; ++l)
                  t.M[index_of(p.master, mn[l])] += phi * q.Nm[l] * q.wJ;
              }
            t.weight += D[kj];
          }
      }
  }

  template <int dim>
  typename Mortar<dim>::template Terms<double>
  Mortar<dim>::terms(const unsigned int i) const
  {
    const auto    all = patches(i);
    Terms<double> sum;
    for (const auto &p : all)
      sum.master_nodes.insert(sum.master_nodes.end(),
                              p.master.begin(),
                              p.master.end());
    std::sort(sum.master_nodes.begin(), sum.master_nodes.end());
    sum.master_nodes.erase(std::unique(sum.master_nodes.begin(),
                                       sum.master_nodes.end()),
                           sum.master_nodes.end());
    sum.M.assign(sum.master_nodes.size(), 0.);
    for (unsigned int member = 0; member < all.size(); ++member)
      {
        const Patch                         &p = all[member];
        std::vector<std::array<double, dim>> xs, xm;
        for (const auto k : p.slave)
          {
            std::array<double, dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = slave_x[k][d];
            xs.push_back(x);
          }
        for (const auto k : p.master)
          {
            std::array<double, dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = this->surface->get_positions()[k][d];
            xm.push_back(x);
          }
        Terms<double> t;
        compute(p, xs, xm, t);
        if (all.size() == 1)
          return t;
        // A hanging node's terms, weighted (the node's own: weight 1).
        add_weighted(t, members[i][member].second, member == 0, sum);
      }
    return sum;
  }

  template <int dim>
  Constraint<dim>
  Mortar<dim>::evaluate(const unsigned int i, const VectorType &U) const
  {
    Constraint<dim> s;
    s.x              = this->position(i, U);
    s.point          = s.x;
    const auto     t = terms(i);
    Tensor<1, dim> n;
    for (unsigned int d = 0; d < dim; ++d)
      n[d] = t.normal[d];
    // The force on the slave pushes it along -n_j (n_j: outward slave
    // normal); Constraint::normal is that direction, as for node to surface
    // (the master's normal).
    s.normal   = -n;
    s.tangents = contact_tangents<dim>(s.normal);
    // A node whose facets the master covers over less than a millionth of
    // its weight has no constraint (as a node beyond the end of the master).
    const double area = (*this->nodes)[i].area;
    if (area > 0.)
      s.coverage = t.weight / area;
    if (t.weight > 1e-6 * area)
      {
        s.outcome = Outcome::found;
        s.gap     = t.weighted_gap / t.weight;
      }
    else
      s.outcome = t.failed ? Outcome::failed : Outcome::beyond_end;
    return s;
  }

  template <int dim>
  void
  Mortar<dim>::linearize(const unsigned int i,
                         const Constraint<dim> &,
                         const VectorType &,
                         Linearization &l) const
  {
    // The union of the slave and master nodes of the node's patches (its
    // own first, so that its slave node comes first), and the terms summed
    // over them with their weights (a hanging node's merged into it).
    const auto                all = patches(i);
    Patch                     p;
    std::vector<unsigned int> masters;
    for (const auto &q : all)
      {
        for (const auto k : q.slave)
          if (std::find(p.slave.begin(), p.slave.end(), k) == p.slave.end())
            p.slave.push_back(k);
        masters.insert(masters.end(), q.master.begin(), q.master.end());
      }
    std::sort(masters.begin(), masters.end());
    masters.erase(std::unique(masters.begin(), masters.end()), masters.end());
    p.master              = masters;
    const unsigned int n  = dim * (p.slave.size() + p.master.size());
    const unsigned int nm = dim * p.slave.size();
    std::vector<std::array<Fad, dim>> xs(p.slave.size()), xm(p.master.size());
    // Values only (a residual): constants, whose derivative arrays are
    // empty, so that the integration costs what compute() with doubles does.
    const auto variable = [&](const unsigned int k, const double x) {
      return l.derivatives ? Fad(n, k, x) : Fad(x);
    };
    l.dofs.clear();
    for (unsigned int a = 0; a < p.slave.size(); ++a)
      for (unsigned int d = 0; d < dim; ++d)
        {
          xs[a][d] = variable(dim * a + d, slave_x[p.slave[a]][d]);
          l.dofs.push_back(slave->get_nodes()[p.slave[a]].dofs[d]);
        }
    for (unsigned int a = 0; a < p.master.size(); ++a)
      for (unsigned int d = 0; d < dim; ++d)
        {
          xm[a][d] = variable(nm + dim * a + d,
                              this->surface->get_positions()[p.master[a]][d]);
          l.dofs.push_back(this->surface->get_nodes()[p.master[a]].dofs[d]);
        }
    Terms<Fad> t;
    if (all.size() == 1)
      compute(all[0], xs, xm, t); // p.slave and p.master are all[0]'s
    else
      {
        t.master_nodes = p.master;
        t.M.assign(p.master.size(), Fad(0.));
        for (unsigned int member = 0; member < all.size(); ++member)
          {
            const Patch                      &q = all[member];
            std::vector<std::array<Fad, dim>> qs, qm;
            for (const auto k : q.slave)
              qs.push_back(xs[index_of(p.slave, k)]);
            for (const auto k : q.master)
              qm.push_back(xm[index_of(p.master, k)]);
            Terms<Fad> tq;
            compute(q, qs, qm, tq);
            add_weighted(tq, members[i][member].second, member == 0, t);
          }
      }
    const Fad g = t.weighted_gap / t.weight;
    // G = dg/dx at fixed n_j, D and M: -n_j on the slave node, (M_jm /
    // D_jj) n_j on master node m.
    std::vector<Fad> G(n, Fad(0.));
    for (unsigned int d = 0; d < dim; ++d)
      G[d] = -t.normal[d];
    for (unsigned int a = 0; a < p.master.size(); ++a)
      for (unsigned int d = 0; d < dim; ++d)
        G[nm + dim * a + d] = t.M[a] / t.weight * t.normal[d];
    l.gap = g.val();
    for (unsigned int d = 0; d < dim; ++d)
      l.normal[d] = -t.normal[d].val();
    l.dgap.reinit(n);
    l.force.reinit(n);
    l.dforce.reinit(n, n);
    for (unsigned int a = 0; a < n; ++a)
      {
        l.dgap(a)  = g.size() > 0 ? g.dx(a) : 0.;
        l.force(a) = G[a].val();
        if (G[a].size() > 0)
          for (unsigned int b = 0; b < n; ++b)
            l.dforce(a, b) = G[a].dx(b);
      }
  }

  template <int dim>
  void
  Mortar<dim>::couplings(const unsigned int                    i,
                         const VectorType                     &U,
                         std::vector<types::global_dof_index> &dofs)
  {
    if (slave_x.empty())
      move(U);
    // The slave nodes of the patch and the master nodes of the facets
    // within twice the search radius (so that the pattern holds while the
    // surfaces slide by up to one facet).
    std::vector<unsigned int> master;
    for (const auto &p : patches(i))
      {
        for (const auto k : p.slave)
          for (unsigned int d = 0; d < dim; ++d)
            dofs.push_back(slave->get_nodes()[k].dofs[d]);
        for (const auto f : p.facets)
          for (const auto c : candidates(f, 2. * radius[f]))
            for (const auto m : this->surface->get_facets()[c].nodes)
              master.push_back(m);
      }
    std::sort(master.begin(), master.end());
    master.erase(std::unique(master.begin(), master.end()), master.end());
    coupled[i] = master;
    for (const auto m : master)
      for (unsigned int d = 0; d < dim; ++d)
        dofs.push_back(this->surface->get_nodes()[m].dofs[d]);
  }

  template <int dim>
  bool
  Mortar<dim>::outside_pattern(const unsigned int i,
                               const Constraint<dim> &) const
  {
    for (const auto &p : patches(i))
      if (!std::includes(coupled[i].begin(),
                         coupled[i].end(),
                         p.master.begin(),
                         p.master.end()))
        return true;
    return false;
  }

  template <int dim>
  void
  Mortar<dim>::commit_step(const VectorType                   &U,
                           const std::vector<Constraint<dim>> &s,
                           const std::vector<bool>            &closed,
                           const double,
                           const double)
  {
    const auto &nodes = *this->nodes;
    move(U);
    this->report_failed(s, "a mortar projection");
    const auto &master_nodes = this->surface->get_nodes();
    for (unsigned int i = 0; i < nodes.size(); ++i)
      {
        // Slip (R12), while closed: the tangential motion of the node
        // relative to the master's material under it, i.e. to the last
        // step's mortar point sum_m (M_jm / D_jj) x_m moved with the
        // master nodes' displacements since. (The current mortar point
        // follows the slave node as it slides, so the motion relative to
        // it was round-off: CSLIP 1e-12 after a slide of 0.6, until
        // 2026-12-07; scene.mortar_slip. The displacements are read from
        // U, not from the facets this process holds: under MPI a step's
        // slip was dropped where the last step's master nodes were no
        // longer gathered, until 2026-12-07.)
        const auto t     = terms(i);
        const bool found = s[i].found();
        if (closed[i] && found && previous_found[i] &&
            !previous_point[i].empty())
          this->accumulate_slip(i,
                                s[i].normal,
                                (s[i].x - previous_position[i]) -
                                  previous_point[i].motion(U));
        previous_point[i].clear();
        if (t.weight > 0.)
          for (unsigned int a = 0; a < t.master_nodes.size(); ++a)
            for (unsigned int d = 0; d < dim; ++d)
              previous_point[i].add(d,
                                    master_nodes[t.master_nodes[a]].dofs[d],
                                    t.M[a] / t.weight,
                                    U);
        previous_position[i] = s[i].x;
        previous_found[i]    = found;
      }
  }

  template class Mortar<2>;
  template class Mortar<3>;
} // namespace glide
