#include <glide/contact/facet_basis.h>
#include <glide/contact/small_sliding.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    using Fad = Sacado::Fad::DFad<double>;
    /// Derivatives with respect to the dim - 1 facet parameters.
    template <int dim>
    using ParameterFad = Sacado::Fad::SFad<double, dim - 1>;

    double
    value_of(const double x)
    {
      return x;
    }
    double
    value_of(const Fad &x)
    {
      return x.val();
    }

    template <typename T, int dim>
    T
    dot(const std::array<T, dim> &a, const std::array<T, dim> &b)
    {
      T s = a[0] * b[0];
      for (int i = 1; i < dim; ++i)
        s += a[i] * b[i];
      return s;
    }

    /// Orthonormal frame of a facet from its tangents a: e_0 along a_0,
    /// e_{dim-1} the outward normal ((a_y, -a_x) in 2D, a_0 x a_1 in 3D).
    template <typename T, int dim>
    std::array<std::array<T, dim>, dim>
    facet_frame(const std::array<std::array<T, dim>, dim - 1> &a)
    {
      using std::sqrt;
      std::array<std::array<T, dim>, dim> e;
      const T                             l0 = sqrt(dot<T, dim>(a[0], a[0]));
      for (int d = 0; d < dim; ++d)
        e[0][d] = a[0][d] / l0;
      if constexpr (dim == 2)
        {
          e[1][0] = e[0][1];
          e[1][1] = -e[0][0];
        }
      else
        {
          std::array<T, 3> c;
          c[0]       = a[0][1] * a[1][2] - a[0][2] * a[1][1];
          c[1]       = a[0][2] * a[1][0] - a[0][0] * a[1][2];
          c[2]       = a[0][0] * a[1][1] - a[0][1] * a[1][0];
          const T lc = sqrt(dot<T, 3>(c, c));
          for (int d = 0; d < 3; ++d)
            e[2][d] = c[d] / lc;
          e[1][0] = e[2][1] * e[0][2] - e[2][2] * e[0][1];
          e[1][1] = e[2][2] * e[0][0] - e[2][0] * e[0][2];
          e[1][2] = e[2][0] * e[0][1] - e[2][1] * e[0][0];
        }
      return e;
    }

    /// Solve the (dim-1)x(dim-1) system G d = r.
    template <typename T, int n>
    std::array<T, n>
    solve_small(const std::array<std::array<T, n>, n> &G,
                const std::array<T, n>                &r)
    {
      std::array<T, n> d;
      if constexpr (n == 1)
        d[0] = r[0] / G[0][0];
      else
        {
          const T det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
          d[0]        = (G[1][1] * r[0] - G[0][1] * r[1]) / det;
          d[1]        = (G[0][0] * r[1] - G[1][0] * r[0]) / det;
        }
      return d;
    }
  } // namespace

  template <int dim>
  SmallSliding<dim>::SmallSliding(
    const MasterSurface<dim>                     &surface,
    const std::map<unsigned int, Tensor<1, dim>> &user_normals,
    const bool                                    infinitesimal,
    const bool                                    axisymmetric)
    : surface(surface)
    , infinitesimal(infinitesimal)
  {
    const auto        &nodes  = surface.get_nodes();
    const auto        &facets = surface.get_facets();
    const unsigned int p      = surface.degree();

    // R7.1: the mean of the normals of the master facets at each node
    // (each facet's normal evaluated at that node), initial coordinates.
    normals.assign(nodes.size(), Tensor<1, dim>());
    node_facets.assign(nodes.size(), {});
    std::vector<double>                      N;
    std::vector<std::array<double, dim - 1>> dN;
    for (unsigned int f = 0; f < facets.size(); ++f)
      {
        const auto &facet = facets[f];
        for (unsigned int k = 0; k < facet.nodes.size(); ++k)
          {
            node_facets[facet.nodes[k]].push_back(f);
            Xi xi;
            xi[0] = double(k % (p + 1)) / p;
            if (dim == 3)
              xi[dim - 2] = double(k / (p + 1)) / p;
            facet_basis<dim, double>(p, xi, N, dN);
            std::array<std::array<double, dim>, dim - 1> a{};
            for (unsigned int j = 0; j < facet.nodes.size(); ++j)
              for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
                for (unsigned int d = 0; d < dim; ++d)
                  a[alpha][d] += dN[j][alpha] * nodes[facet.nodes[j]].X[d];
            const auto e = facet_frame<double, dim>(a);
            for (unsigned int d = 0; d < dim; ++d)
              normals[facet.nodes[k]][d] += e[dim - 1][d];
          }
      }
    for (auto &n : normals)
      n /= n.norm();

    // R8.2: perimeter nodes on a symmetry plane (or on the axis of an
    // axisymmetric scene) get normals in that plane.
    const auto  &symmetric = surface.get_symmetry_flags();
    const double tolerance = 1e-10 * std::max(1., surface.facet_size());
    std::set<unsigned int> perimeter;
    for (const auto &facet : facets)
      for (unsigned int side = 0; side < facet.neighbours.size(); ++side)
        if (facet.neighbours[side] < 0)
          for (unsigned int k = 0; k < facet.nodes.size(); ++k)
            {
              const unsigned int i = k % (p + 1), j = k / (p + 1);
              const bool on_side = dim == 2 ? (side == 0 ? i == 0 : i == p) :
                                              (side == 0 ? i == 0 :
                                               side == 1 ? i == p :
                                               side == 2 ? j == 0 :
                                                           j == p);
              if (on_side)
                perimeter.insert(facet.nodes[k]);
            }
    for (const auto k : perimeter)
      {
        Tensor<1, dim> n = normals[k];
        for (unsigned int c = 0; c < dim; ++c)
          if ((!symmetric.empty() && symmetric[k][c]) ||
              (axisymmetric && c == 0 && std::abs(nodes[k].X[0]) < tolerance))
            n[c] = 0.;
        if (n.norm() > 1e-12)
          normals[k] = n / n.norm();
      }

    // R8.1: user normals replace the computed ones; one that points into
    // the master (against the averaged outward normal) is a mistake (the
    // slave node there went through the master with exit 0 until
    // 2026-12-06).
    for (const auto &[k, n] : user_normals)
      {
        if (inward.empty() && n * normals[k] < 0.)
          {
            std::ostringstream text;
            text << "the normal (" << n << ") given at the master node ("
                 << nodes[k].X
                 << ") points into the master: the master surface's "
                    "outward normal there is ("
                 << normals[k] << ")";
            inward = text.str();
          }
        normals[k] = n / n.norm();
      }

    // Search tree of the facets in the initial configuration, for the
    // anchors.
    std::vector<Leaf> boxes;
    for (unsigned int f = 0; f < facets.size(); ++f)
      {
        Point<dim> lo = nodes[facets[f].nodes[0]].X, hi = lo;
        for (const auto k : facets[f].nodes)
          for (unsigned int d = 0; d < dim; ++d)
            {
              lo[d] = std::min(lo[d], nodes[k].X[d]);
              hi[d] = std::max(hi[d], nodes[k].X[d]);
            }
        boxes.emplace_back(BoundingBox<dim>(std::make_pair(lo, hi)), f);
      }
    tree = pack_rtree(boxes);
  }

  template <int dim>
  Tensor<1, dim>
  SmallSliding<dim>::normal_field(const unsigned int facet, const Xi &xi) const
  {
    std::vector<double>                      N;
    std::vector<std::array<double, dim - 1>> dN;
    facet_basis<dim, double>(surface.degree(), xi, N, dN);
    Tensor<1, dim> n;
    for (unsigned int j = 0; j < N.size(); ++j)
      n += N[j] * normals[surface.get_facets()[facet].nodes[j]];
    return n / n.norm();
  }

  template <int dim>
  bool
  SmallSliding<dim>::anchor_on(const unsigned int facet,
                               const Point<dim>  &X,
                               Xi                &xi,
                               double            &distance) const
  {
    const auto        &nodes = surface.get_nodes();
    const auto        &F     = surface.get_facets()[facet];
    const unsigned int p     = surface.degree();
    double             size  = 0.;
    for (const auto i : F.nodes)
      for (const auto j : F.nodes)
        size = std::max(size, nodes[i].X.distance(nodes[j].X));

    // (r - (r.N) N) . A_alpha = 0 with r = X - X(xi): the line along N(xi)
    // passes through X. Newton, derivatives by automatic differentiation.
    xi.fill(0.5);
    using Fad                                       = ParameterFad<dim>;
    bool                                  converged = false;
    std::vector<Fad>                      N;
    std::vector<std::array<Fad, dim - 1>> dN;
    for (unsigned int it = 0; it < 50 && !converged; ++it)
      {
        std::array<Fad, dim - 1> s;
        for (unsigned int a = 0; a < dim - 1; ++a)
          s[a] = Fad(dim - 1, a, xi[a]);
        facet_basis<dim, Fad>(p, s, N, dN);
        std::array<Fad, dim>                      Xk{}, n{};
        std::array<std::array<Fad, dim>, dim - 1> A{};
        for (unsigned int j = 0; j < N.size(); ++j)
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double y = nodes[F.nodes[j]].X[d];
              Xk[d] += N[j] * y;
              n[d] += N[j] * normals[F.nodes[j]][d];
              for (unsigned int a = 0; a < dim - 1; ++a)
                A[a][d] += dN[j][a] * y;
            }
        const Fad            ln = sqrt(dot<Fad, dim>(n, n));
        std::array<Fad, dim> r;
        for (unsigned int d = 0; d < dim; ++d)
          {
            n[d] /= ln;
            r[d] = X[d] - Xk[d];
          }
        const Fad rn = dot<Fad, dim>(r, n);
        for (unsigned int d = 0; d < dim; ++d)
          r[d] -= rn * n[d];
        std::array<std::array<double, dim - 1>, dim - 1> J;
        std::array<double, dim - 1>                      R;
        for (unsigned int a = 0; a < dim - 1; ++a)
          {
            const Fad Ra = dot<Fad, dim>(r, A[a]);
            R[a]         = -Ra.val();
            for (unsigned int b = 0; b < dim - 1; ++b)
              J[a][b] = Ra.dx(b);
          }
        const double det = dim == 2 ? J[0][0] :
                                      J[0][0] * J[dim - 2][dim - 2] -
                                        J[0][dim - 2] * J[dim - 2][0];
        if (std::abs(det) < 1e-300)
          return false;
        const auto d    = solve_small<double, dim - 1>(J, R);
        double     step = 0.;
        for (unsigned int a = 0; a < dim - 1; ++a)
          {
            xi[a] = std::clamp(xi[a] + d[a], -0.5, 1.5);
            step  = std::max(step, std::abs(d[a]));
          }
        converged = step < 1e-13;
      }
    if (!converged)
      return false;
    for (auto &s : xi)
      {
        if (s < -1e-9 || s > 1. + 1e-9)
          return false;
        s = std::clamp(s, 0., 1.);
      }
    // The line along N(xi) must pass through X (not merely be orthogonal
    // to the tangents), and X must not lie behind the master by more than
    // a facet (the other side of the body).
    std::vector<double>                      Nd;
    std::vector<std::array<double, dim - 1>> dNd;
    facet_basis<dim, double>(p, xi, Nd, dNd);
    Point<dim> Xk;
    for (unsigned int j = 0; j < Nd.size(); ++j)
      Xk += Nd[j] * nodes[F.nodes[j]].X;
    const Tensor<1, dim> n = normal_field(facet, xi);
    const Tensor<1, dim> r = X - Xk;
    distance               = r * n;
    return (r - distance * n).norm() <= 1e-8 * (r.norm() + size) &&
           distance > -size;
  }

  template <int dim>
  template <typename Visit>
  void
  SmallSliding<dim>::search(const Point<dim> &X, const Visit &visit) const
  {
    namespace bgi = boost::geometry::index;
    // Facets near X first; the search widens until visit() reports a hit
    // or every facet has been tried.
    std::set<unsigned int> tried;
    bool                   hit = false;
    for (double radius = 1.5 * surface.facet_size();; radius *= 2.)
      {
        Point<dim> lo = X, hi = X;
        for (unsigned int d = 0; d < dim; ++d)
          {
            lo[d] -= radius;
            hi[d] += radius;
          }
        std::vector<Leaf> candidates;
        tree.query(bgi::intersects(BoundingBox<dim>(std::make_pair(lo, hi))),
                   std::back_inserter(candidates));
        std::sort(candidates.begin(),
                  candidates.end(),
                  [](const Leaf &x, const Leaf &y) {
                    return x.second < y.second;
                  });
        for (const auto &c : candidates)
          if (tried.insert(c.second).second)
            hit = visit(c.second) || hit;
        if (hit || tried.size() == surface.get_facets().size())
          return;
      }
  }

  template <int dim>
  typename SmallSliding<dim>::Anchor
  SmallSliding<dim>::anchor(const Point<dim> &X) const
  {
    const auto &facets = surface.get_facets();
    const auto &nodes  = surface.get_nodes();
    const auto  p      = surface.degree();
    Anchor      a;
    if (facets.empty())
      return a;

    double best = std::numeric_limits<double>::max();
    search(X, [&](const unsigned int facet) {
      Xi     xi;
      double distance;
      if (!anchor_on(facet, X, xi, distance) || std::abs(distance) >= best)
        return false;
      best    = std::abs(distance);
      a.found = true;
      a.facet = facet;
      a.xi    = xi;
      return true;
    });
    if (!a.found)
      return a;

    // X0 at a vertex of its facet: the load list is that node and every
    // node of the facets around it (R11.1).
    const auto &F = facets[a.facet];
    for (unsigned int k = 0; k < F.nodes.size(); ++k)
      {
        const unsigned int i = k % (p + 1), j = k / (p + 1);
        if ((i != 0 && i != p) || (j != 0 && j != p))
          continue;
        const double s = double(i) / p, t = double(j) / p;
        if (std::abs(a.xi[0] - s) < 1e-8 &&
            (dim == 2 || std::abs(a.xi[dim - 2] - t) < 1e-8))
          a.node = F.nodes[k];
      }
    a.facets.push_back(a.facet);
    if (a.node >= 0)
      for (const auto f : node_facets[a.node])
        if (f != a.facet)
          a.facets.push_back(f);
    std::set<unsigned int> list;
    for (const auto f : a.facets)
      list.insert(facets[f].nodes.begin(), facets[f].nodes.end());
    a.list.assign(list.begin(), list.end());

    // Anchor point and plane normal.
    std::vector<double>                      N;
    std::vector<std::array<double, dim - 1>> dN;
    facet_basis<dim, double>(p, a.xi, N, dN);
    for (unsigned int j = 0; j < N.size(); ++j)
      a.X0 += N[j] * nodes[F.nodes[j]].X;
    a.N0 = normal_field(a.facet, a.xi);
    set_frame(a);

    // Initial weights (R6.3).
    a.weights = evaluate_plane(a, X, true).weights;
    return a;
  }

  template <int dim>
  void
  SmallSliding<dim>::set_frame(Anchor &a) const
  {
    const auto &nodes = surface.get_nodes();
    const auto &F     = surface.get_facets()[a.facet];
    // N0 and the initial tangents in the facet's frame at the anchor.
    const auto e        = anchor_frame(a, true);
    const auto tangents = contact_tangents<dim>(a.N0);
    a.frame             = {};
    a.tangent_frame     = {};
    for (unsigned int i = 0; i < dim; ++i)
      {
        a.frame[i] = a.N0 * e[i];
        for (unsigned int t = 0; t < dim - 1; ++t)
          a.tangent_frame[t][i] = tangents[t] * e[i];
      }

    // R12.2: one facet length, less where the master turns by more than
    // 10 degrees over the facet.
    double size = 0., angle = 0.;
    for (const auto i : F.nodes)
      for (const auto j : F.nodes)
        {
          size = std::max(size, nodes[i].X.distance(nodes[j].X));
          angle =
            std::max(angle,
                     std::acos(std::clamp(normals[i] * normals[j], -1., 1.)));
        }
    const double turn = 10. * numbers::PI / 180.;
    a.limit           = size * std::min(1., turn / std::max(angle, 1e-300));
  }

  template <int dim>
  bool
  SmallSliding<dim>::ray(const Point<dim>     &X,
                         const Tensor<1, dim> &direction,
                         unsigned int         &facet,
                         Xi                   &xi,
                         double               &t) const
  {
    const auto                              &facets = surface.get_facets();
    const auto                              &nodes  = surface.get_nodes();
    const auto                               p      = surface.degree();
    bool                                     found  = false;
    std::vector<double>                      N;
    std::vector<std::array<double, dim - 1>> dN;
    search(X, [&](const unsigned int candidate) {
      // Newton on x_F(s) - X - tau d = 0 for (s, tau).
      const auto &F = facets[candidate];
      Xi          s;
      s.fill(0.5);
      double tau       = 0.;
      bool   converged = false;
      for (unsigned int it = 0; it < 30 && !converged; ++it)
        {
          facet_basis<dim, double>(p, s, N, dN);
          Tensor<1, dim>                      R;
          std::array<Tensor<1, dim>, dim - 1> A;
          for (unsigned int j = 0; j < N.size(); ++j)
            {
              const Point<dim> &y = nodes[F.nodes[j]].X;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  R[d] += N[j] * y[d];
                  for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
                    A[alpha][d] += dN[j][alpha] * y[d];
                }
            }
          R -= X + tau * direction;
          FullMatrix<double> J(dim, dim);
          for (unsigned int d = 0; d < dim; ++d)
            {
              for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
                J(d, alpha) = A[alpha][d];
              J(d, dim - 1) = -direction[d];
            }
          if (std::abs(J.determinant()) < 1e-300)
            break;
          FullMatrix<double> inverse(dim, dim);
          inverse.invert(J);
          Vector<double> r(dim), step(dim);
          for (unsigned int d = 0; d < dim; ++d)
            r(d) = -R[d];
          inverse.vmult(step, r);
          double size = 0.;
          for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
            {
              s[alpha] = std::clamp(s[alpha] + step(alpha), -0.5, 1.5);
              size     = std::max(size, std::abs(step(alpha)));
            }
          tau += step(dim - 1);
          converged = size < 1e-13 &&
                      std::abs(step(dim - 1)) < 1e-13 * (1. + std::abs(tau));
        }
      if (!converged)
        return false;
      bool inside = true;
      for (auto &v : s)
        {
          inside = inside && v >= -1e-9 && v <= 1. + 1e-9;
          v      = std::clamp(v, 0., 1.);
        }
      if (!inside || (found && std::abs(tau) >= std::abs(t)))
        return false;
      found = true;
      facet = candidate;
      xi    = s;
      t     = tau;
      return true;
    });
    return found;
  }

  template <int dim>
  typename SmallSliding<dim>::Anchor
  SmallSliding<dim>::anchor_sts(const std::vector<Point<dim>> &X,
                                const std::vector<double>     &phi,
                                const Tensor<1, dim>          &slave_normal,
                                const std::array<bool, dim>   &symmetric,
                                Fallback                      &reason) const
  {
    const auto &facets = surface.get_facets();
    const auto &nodes  = surface.get_nodes();
    const auto  p      = surface.degree();
    Anchor      a;
    reason = Fallback::missed;
    // Where each node of the averaging region, projected along the slave
    // normal, lands on the master.
    std::vector<unsigned int> landing_facet(X.size());
    std::vector<Xi>           landing_xi(X.size());
    for (unsigned int k = 0; k < X.size(); ++k)
      {
        double t;
        if (!ray(X[k], slave_normal, landing_facet[k], landing_xi[k], t))
          return a;
      }
    // Single-sided surfaces face each other: the master normal where the
    // constraint's own node lands must oppose the slave normal.
    std::vector<double>                      N;
    std::vector<std::array<double, dim - 1>> dN;
    a.facet = landing_facet[0];
    a.xi    = landing_xi[0];
    if (anchor_frame(a, true)[dim - 1] * slave_normal >= 0.)
      {
        reason = Fallback::same_direction;
        return a;
      }

    // The anchor: the weighted centre of the landing zone; the master
    // weights: the landing points' shape functions, weighted likewise.
    std::map<unsigned int, double> weight;
    Point<dim>                     centre;
    for (unsigned int k = 0; k < X.size(); ++k)
      {
        facet_basis<dim, double>(p, landing_xi[k], N, dN);
        const auto &F = facets[landing_facet[k]];
        for (unsigned int j = 0; j < N.size(); ++j)
          {
            weight[F.nodes[j]] += phi[k] * N[j];
            a.X0 += phi[k] * N[j] * nodes[F.nodes[j]].X;
          }
        centre += phi[k] * X[k];
      }
    for (const auto &[node, w] : weight)
      {
        a.list.push_back(node);
        a.weights.push_back(w);
      }
    // Contact direction: from the anchor to the region's centre, oriented
    // against the slave normal (R9.2), in symmetry planes (R9.3).
    a.N0 = contact_direction<dim>(
      centre, a.X0, slave_normal, symmetric, 1e-8 * surface.facet_size());
    a.sts   = true;
    a.found = true;
    a.facets.push_back(a.facet);
    set_frame(a);
    reason = Fallback::none;
    return a;
  }

  template <int dim>
  template <typename T, typename Positions>
  void
  SmallSliding<dim>::facet_point(
    const unsigned int                       facet,
    const Xi                                &xi,
    const Positions                         &pos,
    std::array<T, dim>                      &x,
    std::array<std::array<T, dim>, dim - 1> &A) const
  {
    std::vector<double>                      N;
    std::vector<std::array<double, dim - 1>> dN;
    facet_basis<dim, double>(surface.degree(), xi, N, dN);
    x.fill(T(0.));
    for (auto &v : A)
      v.fill(T(0.));
    const auto &F = surface.get_facets()[facet];
    for (unsigned int j = 0; j < N.size(); ++j)
      {
        const auto y = pos(F.nodes[j]);
        for (unsigned int d = 0; d < dim; ++d)
          {
            x[d] += N[j] * y[d];
            for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
              A[alpha][d] += dN[j][alpha] * y[d];
          }
      }
  }

  template <int dim>
  template <typename T, typename Positions>
  void
  SmallSliding<dim>::evaluate(const Anchor             &a,
                              const std::array<T, dim> &xs,
                              const Positions          &pos,
                              const bool                fixed_plane,
                              T                        &gap,
                              std::array<T, dim>       &n,
                              std::array<T, dim>       &x0,
                              std::vector<T>           &w) const
  {
    const auto        &facets = surface.get_facets();
    const auto        &nodes  = surface.get_nodes();
    const unsigned int p      = surface.degree();
    w.assign(a.list.size(), T(0.));
    auto index = [&](const unsigned int k) {
      return std::lower_bound(a.list.begin(), a.list.end(), k) - a.list.begin();
    };

    // The plane normal: the initial one in infinitesimal sliding, else
    // carried by the anchor facet's frame (R10.1).
    std::array<T, dim> x_facet;
    if (fixed_plane)
      for (unsigned int d = 0; d < dim; ++d)
        n[d] = a.N0[d];
    else
      {
        std::array<std::array<T, dim>, dim - 1> A;
        facet_point<T>(a.facet, a.xi, pos, x_facet, A);
        const auto e = facet_frame<T, dim>(A);
        n.fill(T(0.));
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int d = 0; d < dim; ++d)
            n[d] += a.frame[i] * e[i][d];
      }

    if (fixed_plane || a.sts)
      {
        // Infinitesimal sliding, and surface to surface: the initial anchor
        // moved by the weighted master displacements, fixed weights.
        for (unsigned int d = 0; d < dim; ++d)
          x0[d] = a.X0[d];
        for (unsigned int m = 0; m < a.list.size(); ++m)
          {
            const auto y = pos(a.list[m]);
            w[m]         = a.weights[m];
            for (unsigned int d = 0; d < dim; ++d)
              x0[d] += a.weights[m] * (y[d] - nodes[a.list[m]].X[d]);
          }
        gap = T(0.);
        for (unsigned int d = 0; d < dim; ++d)
          gap += (xs[d] - x0[d]) * n[d];
        return;
      }

    // Small sliding: the anchor's material point.
    x0  = x_facet;
    gap = T(0.);
    for (unsigned int d = 0; d < dim; ++d)
      gap += (xs[d] - x0[d]) * n[d];

    // Centre of action: the slave node's projection onto the plane, in the
    // parameters of the anchor facet or, at a node, of the facet around it
    // that contains it (linearized at the anchor), clamped to the facet.
    std::array<T, dim> pc;
    for (unsigned int d = 0; d < dim; ++d)
      pc[d] = xs[d] - gap * n[d];
    unsigned int           chosen = a.facet;
    std::array<T, dim - 1> xi_chosen;
    bool                   inside = false;
    for (unsigned int k = 0; k < a.facets.size() && !inside; ++k)
      {
        const auto &K = facets[a.facets[k]];
        Xi          c = a.xi;
        if (k > 0)
          {
            const unsigned int at =
              std::find(K.nodes.begin(), K.nodes.end(), a.node) -
              K.nodes.begin();
            c[0] = double(at % (p + 1)) / p;
            if (dim == 3)
              c[dim - 2] = double(at / (p + 1)) / p;
          }
        std::array<std::array<T, dim>, dim - 1> b;
        std::array<T, dim>                      xc;
        facet_point<T>(a.facets[k], c, pos, xc, b);
        std::array<std::array<T, dim - 1>, dim - 1> G;
        std::array<T, dim - 1>                      r;
        for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
          {
            r[alpha] = T(0.);
            for (unsigned int d = 0; d < dim; ++d)
              r[alpha] += b[alpha][d] * (pc[d] - xc[d]);
            for (unsigned int beta = 0; beta < dim - 1; ++beta)
              G[alpha][beta] = dot<T, dim>(b[alpha], b[beta]);
          }
        const auto             d = solve_small<T, dim - 1>(G, r);
        std::array<T, dim - 1> xi;
        inside = true;
        for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
          {
            xi[alpha] = c[alpha] + d[alpha];
            inside    = inside && value_of(xi[alpha]) >= -1e-10 &&
                     value_of(xi[alpha]) <= 1. + 1e-10;
          }
        if (k == 0 || inside)
          {
            chosen    = a.facets[k];
            xi_chosen = xi;
          }
      }
    for (auto &s : xi_chosen)
      if (value_of(s) < 0.)
        s = T(0.);
      else if (value_of(s) > 1.)
        s = T(1.);
    std::vector<T>                      NK;
    std::vector<std::array<T, dim - 1>> dNK;
    facet_basis<dim, T>(p, xi_chosen, NK, dNK);
    for (unsigned int j = 0; j < NK.size(); ++j)
      w[index(facets[chosen].nodes[j])] = NK[j];
  }

  template <int dim>
  double
  SmallSliding<dim>::landing_gap(const Anchor         &a,
                                 const Point<dim>     &x,
                                 const Tensor<1, dim> &normal) const
  {
    const auto             &positions = surface.get_positions();
    std::array<double, dim> y;
    std::array<std::array<double, dim>, dim - 1> A;
    facet_point<double>(
      a.facet,
      a.xi,
      [&](const unsigned int k) {
        std::array<double, dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = positions[k][d];
        return p;
      },
      y,
      A);
    double gap = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      gap += (x[d] - y[d]) * normal[d];
    return gap;
  }

  template <int dim>
  typename SmallSliding<dim>::Plane
  SmallSliding<dim>::plane(const Anchor &a, const Point<dim> &x) const
  {
    return evaluate_plane(a, x, false);
  }

  template <int dim>
  typename SmallSliding<dim>::Plane
  SmallSliding<dim>::evaluate_plane(const Anchor     &a,
                                    const Point<dim> &x,
                                    const bool        initial) const
  {
    const auto             &positions = surface.get_positions();
    const auto             &nodes     = surface.get_nodes();
    std::array<double, dim> xs, n, x0;
    for (unsigned int d = 0; d < dim; ++d)
      xs[d] = x[d];
    Plane result;
    evaluate<double>(
      a,
      xs,
      [&](const unsigned int k) {
        std::array<double, dim> y;
        for (unsigned int d = 0; d < dim; ++d)
          y[d] = initial ? nodes[k].X[d] : positions[k][d];
        return y;
      },
      infinitesimal && !initial,
      result.gap,
      n,
      x0,
      result.weights);
    for (unsigned int d = 0; d < dim; ++d)
      {
        result.point[d]  = x0[d];
        result.normal[d] = n[d];
      }
    // The initial tangents, turned with the facet (R13.1, R10.1).
    const auto e = anchor_frame(a, initial || infinitesimal);
    for (unsigned int t = 0; t < dim - 1; ++t)
      for (unsigned int i = 0; i < dim; ++i)
        result.tangents[t] += a.tangent_frame[t][i] * e[i];
    return result;
  }

  template <int dim>
  std::array<Tensor<1, dim>, dim>
  SmallSliding<dim>::anchor_frame(const Anchor &a, const bool initial) const
  {
    const auto                              &F = surface.get_facets()[a.facet];
    std::vector<double>                      N;
    std::vector<std::array<double, dim - 1>> dN;
    facet_basis<dim, double>(surface.degree(), a.xi, N, dN);
    std::array<std::array<double, dim>, dim - 1> A{};
    for (unsigned int j = 0; j < N.size(); ++j)
      {
        const Point<dim> &y = initial ? surface.get_nodes()[F.nodes[j]].X :
                                        surface.get_positions()[F.nodes[j]];
        for (unsigned int alpha = 0; alpha < dim - 1; ++alpha)
          for (unsigned int d = 0; d < dim; ++d)
            A[alpha][d] += dN[j][alpha] * y[d];
      }
    const auto                      e = facet_frame<double, dim>(A);
    std::array<Tensor<1, dim>, dim> frame;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int d = 0; d < dim; ++d)
        frame[i][d] = e[i][d];
    return frame;
  }

  template <int dim>
  std::vector<double>
  SmallSliding<dim>::weights(const Anchor &a, const Point<dim> &x) const
  {
    return evaluate_plane(a, x, false).weights;
  }

  template <int dim>
  void
  SmallSliding<dim>::linearize(
    const Anchor                                        &a,
    const std::vector<std::pair<SlaveDofs, Point<dim>>> &slaves,
    Linearization                                       &l) const
  {
    const auto        &positions = surface.get_positions();
    const auto        &nodes     = surface.get_nodes();
    const unsigned int n_slave   = slaves.size();
    const unsigned int n_var     = dim * (n_slave + a.list.size());
    // The constraint's slave point: the node, or the participation-weighted
    // centre of the averaging region.
    std::array<Fad, dim> xs;
    for (auto &v : xs)
      v = Fad(0.);
    for (unsigned int k = 0; k < n_slave; ++k)
      {
        const double phi = a.sts ? a.participation[k] : 1.;
        for (unsigned int d = 0; d < dim; ++d)
          xs[d] += phi * Fad(n_var, dim * k + d, slaves[k].second[d]);
      }
    Fad                  gap;
    std::array<Fad, dim> n, x0;
    std::vector<Fad>     w;
    evaluate<Fad>(
      a,
      xs,
      [&](const unsigned int k) {
        const unsigned int m =
          std::lower_bound(a.list.begin(), a.list.end(), k) - a.list.begin();
        std::array<Fad, dim> y;
        for (unsigned int d = 0; d < dim; ++d)
          y[d] = Fad(n_var, dim * (n_slave + m) + d, positions[k][d]);
        return y;
      },
      infinitesimal,
      gap,
      n,
      x0,
      w);

    l.dofs.clear();
    for (const auto &slave : slaves)
      l.dofs.insert(l.dofs.end(), slave.first.begin(), slave.first.end());
    for (const auto k : a.list)
      for (unsigned int d = 0; d < dim; ++d)
        l.dofs.push_back(nodes[k].dofs[d]);
    l.gap = gap.val();
    for (unsigned int d = 0; d < dim; ++d)
      l.normal[d] = n[d].val();
    l.dgap.reinit(n_var);
    l.force.reinit(n_var);
    l.dforce.reinit(n_var, n_var);
    // Force direction: phi_k n on slave node k, -w_m n on master node m.
    for (unsigned int i = 0; i < n_var; ++i)
      {
        const unsigned int m = i / dim, d = i % dim;
        const Fad          G = m < n_slave ?
                                 Fad((a.sts ? a.participation[m] : 1.) * n[d]) :
                                 Fad(-w[m - n_slave] * n[d]);
        l.force(i)           = G.val();
        l.dgap(i)            = gap.dx(i);
        for (unsigned int j = 0; j < n_var; ++j)
          l.dforce(i, j) = G.dx(j);
      }
  }

  template class SmallSliding<2>;
  template class SmallSliding<3>;
} // namespace glide
