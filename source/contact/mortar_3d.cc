#include <glide/contact/mortar.h>
#include <glide/contact/mortar_geometry.h>

#include <Sacado.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <unordered_map>

namespace glide
{
  using namespace dealii;

  namespace
  {
    // Small helpers as in mortar.cc (kept local to this file so that the
    // 2D code stays untouched).

    using mortar_geometry::value;

    /// Unit vector along @p a (a must not vanish).
    template <typename T>
    std::array<T, 3>
    unit3(const std::array<T, 3> &a)
    {
      using std::sqrt;
      const T l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
      return {{a[0] / l, a[1] / l, a[2] / l}};
    }

    template <typename T>
    std::array<T, 3>
    cross3(const std::array<T, 3> &a, const std::array<T, 3> &b)
    {
      return {{a[1] * b[2] - a[2] * b[1],
               a[2] * b[0] - a[0] * b[2],
               a[0] * b[1] - a[1] * b[0]}};
    }


    /// Index of @p k in @p list (which holds it).
    unsigned int
    index_of(const std::vector<unsigned int> &list, const unsigned int k)
    {
      return std::find(list.begin(), list.end(), k) - list.begin();
    }

    /// Bilinear shape functions of a quadrilateral facet (lexicographic
    /// nodes) at @p xi, and their derivatives.
    template <typename T>
    void
    bilinear(const std::array<T, 2> &xi,
             std::array<T, 4>       &N,
             std::array<T, 4>       &Ns,
             std::array<T, 4>       &Nt)
    {
      const T s = xi[0], t = xi[1];
      N  = {{(1. - s) * (1. - t), s * (1. - t), (1. - s) * t, s * t}};
      Ns = {{t - 1., 1. - t, -t, t}};
      Nt = {{s - 1., -s, 1. - s, s}};
    }

    /// Position and tangents a_1, a_2 of the bilinear facet with corners
    /// @p X at @p xi.
    template <typename T>
    void
    facet_point(const std::array<std::array<T, 3>, 4> &X,
                const std::array<T, 2>                &xi,
                std::array<T, 4>                      &N,
                std::array<T, 3>                      &x,
                std::array<T, 3>                      &a1,
                std::array<T, 3>                      &a2)
    {
      std::array<T, 4> Ns, Nt;
      bilinear(xi, N, Ns, Nt);
      for (unsigned int d = 0; d < 3; ++d)
        {
          x[d] = a1[d] = a2[d] = 0.;
          for (unsigned int k = 0; k < 4; ++k)
            {
              x[d] += N[k] * X[k][d];
              a1[d] += Ns[k] * X[k][d];
              a2[d] += Nt[k] * X[k][d];
            }
        }
    }

    /// The corners (lexicographic) of a facet's edges xi = 0, xi = 1,
    /// eta = 0, eta = 1 (the order of MasterSurface::Facet::neighbours).
    constexpr unsigned int edge_corners[4][2] = {{0, 2},
                                                 {1, 3},
                                                 {0, 1},
                                                 {2, 3}};

    using Corners = std::array<std::array<double, 3>, 4>;

    /// Whether the master facet with corners @p Y faces the slave facet
    /// with corners @p X (normals opposed at the centres) and their
    /// projections onto the slave facet's auxiliary plane overlap; on
    /// values (the test that compute_3d() makes before integrating).
    bool
    facing_overlap(const Corners &X, const Corners &Y, bool *convex = nullptr)
    {
      namespace mg = mortar_geometry;
      std::array<double, 4> N;
      std::array<double, 3> x, a1, a2, y, b1, b2;
      facet_point(X, {{0.5, 0.5}}, N, x, a1, a2);
      facet_point(Y, {{0.5, 0.5}}, N, y, b1, b2);
      const auto n = unit3(cross3(a1, a2));
      const auto m = cross3(b1, b2);
      if (m[0] * n[0] + m[1] * n[1] + m[2] * n[2] >= 0.)
        return false;
      const auto                         plane = mg::make_plane(x, n);
      std::array<mg::Point2D<double>, 4> Ps, Pm;
      for (unsigned int v = 0; v < 4; ++v)
        {
          Ps[v] = mg::to_plane(plane, X[v]);
          Pm[v] = mg::to_plane(plane, Y[v]);
        }
      const auto master = mg::quadrilateral_polygon(Pm);
      if (convex != nullptr)
        *convex = mg::is_convex(master);
      return !mg::clip(mg::quadrilateral_polygon(Ps), master).empty();
    }

    /// Bilinear defect of a quadrilateral with corners @p P (lexicographic,
    /// two or three coordinates) over the polygon @p piece of its plane:
    /// |P_0 - P_1 - P_2 + P_3| over the quadrilateral's longer diagonal
    /// (zero for a parallelogram), times the ratio of the piece's diameter
    /// to that diagonal where the piece is smaller. The restriction of a
    /// bilinear map to a part of relative size sigma of its parameter
    /// square is a bilinear map with sigma times the relative defect.
    template <std::size_t n>
    double
    bilinear_defect(const std::array<std::array<double, n>, 4> &P,
                    const double                                piece)
    {
      double defect = 0., d03 = 0., d12 = 0.;
      for (unsigned int d = 0; d < n; ++d)
        {
          const double b = P[0][d] - P[1][d] - P[2][d] + P[3][d];
          defect += b * b;
          d03 += (P[3][d] - P[0][d]) * (P[3][d] - P[0][d]);
          d12 += (P[2][d] - P[1][d]) * (P[2][d] - P[1][d]);
        }
      const double diagonal = std::sqrt(std::max(d03, d12));
      return std::sqrt(defect) / diagonal * std::min(1., piece / diagonal);
    }

    /// Degree of the polygon rule for the clip polygon @p overlap of a
    /// slave facet with corners @p X and a master facet whose corners
    /// project to @p Pm in the slave's auxiliary plane. If the slave facet
    /// is a flat parallelogram and the master's projection a
    /// parallelogram, every integrand of pair_moments() is a polynomial of
    /// degree at most 4 in the plane and degree 5 is exact. Otherwise the
    /// inverse bilinear maps make the integrands rational, and the error
    /// of a rule falls with the larger bilinear_defect() delta of the two
    /// like a power of delta that grows with the degree (unit test
    /// MortarGeometry.ShapeFunctionIntegralsOnDistortedQuadrilaterals:
    /// largest relative error of int N_k 7e-13 with degree 5 at delta =
    /// 0.005, 7e-13 with degree 7 at 0.05, 1e-13 with degree 11 at 0.15,
    /// 3e-13 with degree 13 at 0.2, 3e-10 at 0.3). The rule is the
    /// cheapest that keeps that error below 1e-12, so that the patch test
    /// passes to round-off on general flat quadrilaterals too (R14.5), at
    /// 15, 28 or 37 points per triangle instead of 7 where facets are
    /// distorted.
    template <typename S>
    unsigned int
    rule_degree(const Corners                                         &X,
                const std::array<mortar_geometry::Point2D<double>, 4> &Pm,
                const mortar_geometry::Polygon<S>                     &overlap)
    {
      double piece = 0.;
      for (const auto &a : overlap)
        for (const auto &b : overlap)
          piece = std::max(piece,
                           std::hypot(value(a[0]) - value(b[0]),
                                      value(a[1]) - value(b[1])));
      const double delta =
        std::max(bilinear_defect(X, piece), bilinear_defect(Pm, piece));
      if (delta <= 5e-3)
        return 5;
      if (delta <= 0.05)
        return 7;
      if (delta <= 0.15)
        return 11;
      return 13;
    }

    /// The integrals over the overlap of one slave facet (corners @p X,
    /// nodal normals @p n) with one master facet (corners @p Y) that the
    /// terms of compute_3d() are made of (k, l: slave nodes; m: master
    /// nodes of the pair):
    /// D_k = int N_k dA, MS_kl = int N_k N_l dA, G_k = int N_k g dA,
    /// MM_km = int N_k N^m_m dA.
    template <typename S>
    struct PairMoments
    {
      std::array<S, 4>                D, G;
      std::array<std::array<S, 4>, 4> MS, MM;
      /// An inverse map that did not converge, or a degenerate point.
      bool failed = false;
    };

    /// PairMoments of a slave facet and a master facet that face each
    /// other and overlap (facing_overlap()), the master's projection being
    /// convex. In the scalar type S; the decisions on values.
    template <typename S>
    void
    pair_moments(const std::array<std::array<S, 3>, 4> &X,
                 const std::array<std::array<S, 3>, 4> &n,
                 const std::array<std::array<S, 3>, 4> &Y,
                 PairMoments<S>                        &r)
    {
      namespace mg = mortar_geometry;
      using V      = std::array<S, 3>;
      using P2     = mg::Point2D<S>;
      for (unsigned int k = 0; k < 4; ++k)
        {
          r.D[k] = r.G[k] = 0.;
          for (unsigned int l = 0; l < 4; ++l)
            r.MS[k][l] = r.MM[k][l] = 0.;
        }
      // The auxiliary plane: through the centre, normal to the facet
      // there.
      std::array<S, 4> N;
      V                centre, a1, a2;
      facet_point(X, std::array<S, 2>{{S(0.5), S(0.5)}}, N, centre, a1, a2);
      const auto        plane = mg::make_plane(centre, unit3(cross3(a1, a2)));
      std::array<P2, 4> Ps, Pm;
      for (unsigned int v = 0; v < 4; ++v)
        {
          Ps[v] = mg::to_plane(plane, X[v]);
          Pm[v] = mg::to_plane(plane, Y[v]);
        }
      const mg::Polygon<S> overlap =
        mg::clip(mg::quadrilateral_polygon(Ps), mg::quadrilateral_polygon(Pm));
      Corners                            Xd;
      std::array<mg::Point2D<double>, 4> Pmd;
      for (unsigned int v = 0; v < 4; ++v)
        {
          for (unsigned int d = 0; d < 3; ++d)
            Xd[v][d] = value(X[v][d]);
          Pmd[v] = {{value(Pm[v][0]), value(Pm[v][1])}};
        }
      const auto converged = [](const mg::InverseMapStatus s) {
        return s == mg::InverseMapStatus::inside ||
               s == mg::InverseMapStatus::outside;
      };
      for (const auto &q :
           mg::quadrature(overlap, rule_degree(Xd, Pmd, overlap)))
        {
          const auto is = mg::inverse_bilinear_map(Ps, q.point);
          const auto im = mg::inverse_bilinear_map(Pm, q.point);
          if (!converged(is.status) || !converged(im.status))
            {
              r.failed = true;
              continue;
            }
          std::array<S, 4> Ns, Nm, Nxi, Neta;
          V                x, y, b1, b2;
          facet_point(X, is.xi, Ns, x, a1, a2);
          facet_point(Y, im.xi, Nm, y, b1, b2);
          V nn{{S(0.), S(0.), S(0.)}};
          for (unsigned int k = 0; k < 4; ++k)
            for (unsigned int d = 0; d < 3; ++d)
              nn[d] += Ns[k] * n[k][d];
          nn = unit3(nn);
          // Area element of the slave facet and of its projection in the
          // plane at xi_s.
          const auto area = cross3(a1, a2);
          using std::sqrt;
          const S da =
            sqrt(area[0] * area[0] + area[1] * area[1] + area[2] * area[2]);
          bilinear(is.xi, N, Nxi, Neta);
          P2 p1{{S(0.), S(0.)}}, p2{{S(0.), S(0.)}};
          for (unsigned int k = 0; k < 4; ++k)
            for (unsigned int d = 0; d < 2; ++d)
              {
                p1[d] += Nxi[k] * Ps[k][d];
                p2[d] += Neta[k] * Ps[k][d];
              }
          S dp = p1[0] * p2[1] - p1[1] * p2[0];
          if (value(dp) < 0.)
            dp = -dp;
          if (!(value(dp) > 0.))
            {
              r.failed = true;
              continue;
            }
          const S wJ  = q.weight * da / dp;
          const S gap = nn[0] * (y[0] - x[0]) + nn[1] * (y[1] - x[1]) +
                        nn[2] * (y[2] - x[2]);
          for (unsigned int k = 0; k < 4; ++k)
            {
              const S Nw = Ns[k] * wJ;
              r.D[k] += Nw;
              r.G[k] += Nw * gap;
              for (unsigned int l = 0; l < 4; ++l)
                {
                  r.MS[k][l] += Nw * Ns[l];
                  r.MM[k][l] += Nw * Nm[l];
                }
            }
        }
    }

    /// The moments of a pair in the fixed-size Fad of pair_moments_in().
    using LocalFad = Sacado::Fad::SFad<double, 36>;

    /// 36 NaN: the inputs of a new memo entry, equal to none.
    std::array<double, 36>
    no_inputs()
    {
      std::array<double, 36> a;
      a.fill(std::numeric_limits<double>::quiet_NaN());
      return a;
    }

    /// A memo entry: the 36 input values (X, n, Y) and the moments.
    template <typename S>
    struct PairEntry
    {
      std::array<double, 36> inputs = no_inputs();
      PairMoments<S>         moments;
    };

    /// The memo of pair moments: in double (residuals) and in LocalFad
    /// (Jacobians), keyed by slave facet and master facet.
    struct PairMemo
    {
      std::unordered_map<std::uint64_t, PairEntry<double>>   plain;
      std::unordered_map<std::uint64_t, PairEntry<LocalFad>> local;
    };

    /// pair_moments() with memo: the entry of @p key in @p memo if its
    /// inputs are @p inputs, else computed by @p compute and stored.
    template <typename S, typename F>
    const PairMoments<S> &
    remembered(std::unordered_map<std::uint64_t, PairEntry<S>> &memo,
               const std::uint64_t                              key,
               const std::array<double, 36>                    &inputs,
               const F                                         &compute)
    {
      auto &e = memo[key];
      if (e.inputs != inputs) // a new entry's NaN inputs equal nothing
        {
          e.inputs = inputs;
          compute(e.moments);
        }
      return e.moments;
    }

    /// pair_moments() in T. For T = double directly; for a Fad T the
    /// moments are computed with a fixed-size Fad in the 36 coordinates of
    /// X, n and Y only, and their derivatives carried over to T by the
    /// chain rule (the same derivatives, at a fraction of the cost of
    /// differentiating every quadrature point with respect to all the
    /// patch's coordinates). Both through the memo @p memo under @p key
    /// (the slave and master facets): the patches of the slave facet's
    /// other nodes integrate the same pair.
    template <typename T>
    void
    pair_moments_in(const std::array<std::array<T, 3>, 4> &X,
                    const std::array<std::array<T, 3>, 4> &n,
                    const std::array<std::array<T, 3>, 4> &Y,
                    PairMoments<T>                        &r,
                    const std::uint64_t                    key,
                    PairMemo                              &memo)
    {
      std::array<double, 36> inputs;
      for (unsigned int v = 0; v < 4; ++v)
        for (unsigned int d = 0; d < 3; ++d)
          {
            inputs[3 * v + d]      = value(X[v][d]);
            inputs[12 + 3 * v + d] = value(n[v][d]);
            inputs[24 + 3 * v + d] = value(Y[v][d]);
          }
      if constexpr (std::is_same_v<T, double>)
        r = remembered(memo.plain, key, inputs, [&](PairMoments<double> &m) {
          pair_moments(X, n, Y, m);
        });
      else
        {
          using L = LocalFad;
          std::array<const T *, 36> in;
          for (unsigned int v = 0; v < 4; ++v)
            for (unsigned int d = 0; d < 3; ++d)
              {
                const unsigned int i = 3 * v + d;
                in[i]                = &X[v][d];
                in[12 + i]           = &n[v][d];
                in[24 + i]           = &Y[v][d];
              }
          // Constants (a residual: Mortar::linearize() without
          // derivatives): the moments in double.
          if (std::all_of(in.begin(), in.end(), [](const T *x) {
                return x->size() == 0;
              }))
            {
              const auto &plain = remembered(
                memo.plain, key, inputs, [&](PairMoments<double> &m) {
                  std::array<std::array<double, 3>, 4> Xd, nd, Yd;
                  for (unsigned int v = 0; v < 4; ++v)
                    for (unsigned int d = 0; d < 3; ++d)
                      {
                        Xd[v][d] = inputs[3 * v + d];
                        nd[v][d] = inputs[12 + 3 * v + d];
                        Yd[v][d] = inputs[24 + 3 * v + d];
                      }
                  pair_moments(Xd, nd, Yd, m);
                });
              r.failed = plain.failed;
              for (unsigned int k = 0; k < 4; ++k)
                {
                  r.D[k] = plain.D[k];
                  r.G[k] = plain.G[k];
                  for (unsigned int l = 0; l < 4; ++l)
                    {
                      r.MS[k][l] = plain.MS[k][l];
                      r.MM[k][l] = plain.MM[k][l];
                    }
                }
              return;
            }
          const auto &local =
            remembered(memo.local, key, inputs, [&](PairMoments<L> &m) {
              std::array<std::array<L, 3>, 4> Xl, nl, Yl;
              for (unsigned int v = 0; v < 4; ++v)
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    const unsigned int i = 3 * v + d;
                    Xl[v][d]             = L(36, i, inputs[i]);
                    nl[v][d]             = L(36, 12 + i, inputs[12 + i]);
                    Yl[v][d]             = L(36, 24 + i, inputs[24 + i]);
                  }
              pair_moments(Xl, nl, Yl, m);
            });
          r.failed        = local.failed;
          const auto lift = [&in](const L &a) {
            T b = a.val();
            for (unsigned int i = 0; i < 36; ++i)
              if (a.dx(i) != 0.)
                b += a.dx(i) * (*in[i] - value(*in[i]));
            return b;
          };
          for (unsigned int k = 0; k < 4; ++k)
            {
              r.D[k] = lift(local.D[k]);
              r.G[k] = lift(local.G[k]);
              for (unsigned int l = 0; l < 4; ++l)
                {
                  r.MS[k][l] = lift(local.MS[k][l]);
                  r.MM[k][l] = lift(local.MM[k][l]);
                }
            }
        }
    }
  } // namespace

  template <int dim>
  struct Mortar<dim>::PairCache
  {
    PairMemo memo;
  };

  /**
   * Mortar terms in 3D (R14.2; Popp, Gitterle, Gee and Wall 2010),
   * bilinear quadrilateral facets (degree 1; make_formulation() refuses
   * degree 2 in 3D, R14.7):
   *
   * - nodal normal n_k: the mean of the unit normals of the slave facets
   *   at node k, evaluated at that node; at the boundary of the slave
   *   surface on a symmetry plane (XSYMM, YSYMM, ZSYMM) its component
   *   normal to the plane is dropped (the mirror image's facets would
   *   cancel it), then normalized. The normal field is n(xi) = sum_k
   *   N_k(xi) n_k, normalized.
   * - per slave facet at j: the auxiliary plane through the facet centre
   *   with the facet's unit normal there; the slave facet's corners and
   *   each candidate master facet's corners (master facets facing the
   *   slave only) are projected onto it along its normal and the
   *   projections are clipped (mortar_geometry::clip()). The clip polygon
   *   is integrated with the degree-5 polygon rule; at each quadrature
   *   point the slave and master parameters are those whose projections
   *   are the point (inverse bilinear maps in the plane), and
   *   g = n(xi_s) . (x_m - x_s).
   * - the weight of a point is its weight in the plane times the ratio of
   *   the slave facet's area element |a_1 x a_2| to that of its projection
   *   at xi_s, so that the integrals are over the slave surface. For flat
   *   facets the ratio is one and the integrals of the polynomial
   *   integrands of a flat interface are exact; curved (warped) facets are
   *   integrated approximately, through the planar projection, as in Popp
   *   et al.
   * - the integrals are collected per pair of slave and master facet
   *   (pair_moments()); the consistent dual basis on the covered part and
   *   D_jj, g~_j and M_jm follow from them as in the 2D compute().
   */
  template <int dim>
  template <typename T>
  void
  Mortar<dim>::compute_3d(const Patch                           &p,
                          const std::vector<std::array<T, dim>> &xs,
                          const std::vector<std::array<T, dim>> &xm,
                          Terms<T>                              &t) const
  {
    static_assert(dim == 3, "compute_3d() is the 3D part of compute()");
    using V               = std::array<T, 3>;
    const auto &s_facets  = slave->get_facets();
    const auto &m_facets  = this->surface->get_facets();
    const auto &symmetric = slave->get_symmetry_flags();
    AssertThrow(slave->degree() == 1 && this->surface->degree() == 1,
                ExcMessage("mortar contact in 3D needs facets of degree 1"));

    // p.master is sorted (patch()).
    const auto master_index = [&](const unsigned int m) -> unsigned int {
      return std::lower_bound(p.master.begin(), p.master.end(), m) -
             p.master.begin();
    };
    const auto slave_corners = [&](const unsigned int f) {
      std::array<V, 4> X;
      for (unsigned int v = 0; v < 4; ++v)
        X[v] = xs[index_of(p.slave, s_facets[f].nodes[v])];
      return X;
    };
    // Outward unit normal a_1 x a_2 / |a_1 x a_2| of a facet at xi.
    const auto facet_normal = [](const std::array<V, 4> &X,
                                 const std::array<T, 2> &xi) {
      std::array<T, 4> N;
      V                x, a1, a2;
      facet_point(X, xi, N, x, a1, a2);
      return unit3(cross3(a1, a2));
    };
    if (!pair_cache)
      pair_cache = std::make_shared<PairCache>();
    PairMemo &memo = pair_cache->memo;
    // Nodal normals of the patch's slave nodes, computed when needed.
    std::vector<V>    nodal(p.slave.size());
    std::vector<bool> have(p.slave.size(), false);
    const auto        nodal_normal = [&](const unsigned int k) -> V {
      const unsigned int a = index_of(p.slave, k);
      if (!have[a])
        {
          V    n{{T(0.), T(0.), T(0.)}};
          bool boundary = false;
          for (const auto f : facets_at[k])
            {
              const unsigned int     v = index_of(s_facets[f].nodes, k);
              const std::array<T, 2> corner{
                {T(double(v % 2)), T(double(v / 2))}};
              const auto m = facet_normal(slave_corners(f), corner);
              for (unsigned int d = 0; d < 3; ++d)
                n[d] += m[d];
              for (unsigned int e = 0; e < 4; ++e)
                if ((edge_corners[e][0] == v || edge_corners[e][1] == v) &&
                    s_facets[f].neighbours[e] < 0)
                  boundary = true;
            }
          if (boundary)
            for (unsigned int c = 0; c < 3; ++c)
              if (symmetric[k][c])
                n[c] = 0.;
          nodal[a] = unit3(n);
          have[a]  = true;
        }
      return nodal[a];
    };
    t.normal = nodal_normal(p.slave[0]);

    for (const unsigned int f : p.facets)
      {
        const auto       X = slave_corners(f);
        std::array<V, 4> n;
        Corners          Xd;
        for (unsigned int v = 0; v < 4; ++v)
          {
            n[v]  = nodal_normal(s_facets[f].nodes[v]);
            Xd[v] = value(X[v]);
          }
        // Sums over the master facets of the moments (pair_moments()).
        std::array<T, 4>            D, G;
        std::vector<std::vector<T>> MS(4, std::vector<T>(4));
        std::vector<std::pair<unsigned int, PairMoments<T>>> pairs;
        for (unsigned int k = 0; k < 4; ++k)
          {
            D[k] = G[k] = 0.;
            for (unsigned int l = 0; l < 4; ++l)
              MS[k][l] = 0.;
          }
        for (const unsigned int c : p.candidates[index_of(p.facets, f)])
          {
            std::array<V, 4> Y;
            Corners          Yd;
            for (unsigned int v = 0; v < 4; ++v)
              {
                Y[v]  = xm[master_index(m_facets[c].nodes[v])];
                Yd[v] = value(Y[v]);
              }
            // Only master facets that face the slave facet and overlap it
            // in the plane (decided on the values).
            bool convex = false;
            if (!facing_overlap(Xd, Yd, &convex))
              continue;
            // clip() needs a convex master: a master facet whose
            // projection is not convex (strongly warped, or seen edge-on)
            // is not integrated.
            if (!convex)
              {
                t.failed = true;
                continue;
              }
            pairs.emplace_back(c, PairMoments<T>());
            auto &r = pairs.back().second;
            pair_moments_in(
              X, n, Y, r, std::uint64_t(f) * m_facets.size() + c, memo);
            t.failed = t.failed || r.failed;
            for (unsigned int k = 0; k < 4; ++k)
              {
                D[k] += r.D[k];
                G[k] += r.G[k];
                for (unsigned int l = 0; l < 4; ++l)
                  MS[k][l] += r.MS[k][l];
              }
          }
        if (pairs.empty())
          continue;
        // The dual basis on the covered part: A = D MS^{-1} (as in 2D);
        // Phi_j = sum_l A_l N_l, so int Phi_j g dA = sum_l A_l G_l and
        // int Phi_j N^m dA = sum_l A_l MM_lm.
        if (!mortar_geometry::invert_small(MS))
          continue;
        const unsigned int kj = index_of(s_facets[f].nodes, p.slave[0]);
        std::array<T, 4>   A;
        for (unsigned int l = 0; l < 4; ++l)
          A[l] = D[kj] * MS[kj][l];
        for (unsigned int l = 0; l < 4; ++l)
          t.weighted_gap += A[l] * G[l];
        for (const auto &[c, r] : pairs)
          {
            const auto &mn = m_facets[c].nodes;
            for (unsigned int m = 0; m < 4; ++m)
              {
                T sum = 0.;
                for (unsigned int l = 0; l < 4; ++l)
                  sum += A[l] * r.MM[l][m];
                t.M[master_index(mn[m])] += sum;
              }
          }
        t.weight += D[kj];
      }
  }

  template <int dim>
  bool
  Mortar<dim>::overlaps_3d(const unsigned int facet,
                           const unsigned int master) const
  {
    Corners     X, Y;
    const auto &xm = this->surface->get_positions();
    for (unsigned int v = 0; v < 4; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        {
          X[v][d] = slave_x[slave->get_facets()[facet].nodes[v]][d];
          Y[v][d] = xm[this->surface->get_facets()[master].nodes[v]][d];
        }
    return facing_overlap(X, Y);
  }

  template bool
  Mortar<3>::overlaps_3d(const unsigned int, const unsigned int) const;

  template void
  Mortar<3>::compute_3d<double>(const Patch &,
                                const std::vector<std::array<double, 3>> &,
                                const std::vector<std::array<double, 3>> &,
                                Terms<double> &) const;
  template void
  Mortar<3>::compute_3d<Sacado::Fad::DFad<double>>(
    const Patch &,
    const std::vector<std::array<Sacado::Fad::DFad<double>, 3>> &,
    const std::vector<std::array<Sacado::Fad::DFad<double>, 3>> &,
    Terms<Sacado::Fad::DFad<double>> &) const;
} // namespace glide
