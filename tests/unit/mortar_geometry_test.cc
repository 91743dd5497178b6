// Unit tests of the mortar geometry unit (R14.2): overlap of parameter
// intervals (2D segments), clipping of projected facets (3D polygons),
// areas, centroids, the degree-5 triangle rule and polygon quadrature,
// projection onto the auxiliary plane, inverse facet maps, and the
// derivatives of clipped areas and integrals (R14.4 needs them). Why the
// expected answers are right is said at each test: areas and integrals
// have closed forms (hand-computed overlaps, x^a y^b over triangles
// a! b! / (a + b + 2)!, over any polygon Steger's exact edge formula), maps
// are checked by round trips, derivatives against central differences.
#include <glide/contact/mortar_geometry.h>

#include <deal.II/base/exceptions.h>

#include <Sacado.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace mg = glide::mortar_geometry;

namespace
{
  using Fad   = Sacado::Fad::DFad<double>;
  using P     = mg::Point2D<double>;
  using Poly  = mg::Polygon<double>;
  using Point = std::array<std::int64_t, 2>;

  /// n! as a double (exact for the small n used here).
  double
  factorial(const int n)
  {
    double f = 1.;
    for (int i = 2; i <= n; ++i)
      f *= i;
    return f;
  }

  /// Binomial coefficient C(n, k), exact in integers for small n.
  std::int64_t
  binomial(const int n, const int k)
  {
    std::int64_t c = 1;
    for (int i = 1; i <= k; ++i)
      c = c * (n - k + i) / i;
    return c;
  }

  /// Exact integral of x^p y^q over the polygon with integer vertices
  /// @p vertices (counter-clockwise), by Steger's formula (the polygon is a
  /// fan of signed triangles from the origin, and x^p y^q over each has the
  /// Dirichlet closed form):
  /// `p! q! / (p+q+2)! sum_i (x_i y_{i+1} - x_{i+1} y_i)
  ///  sum_{k<=p, l<=q} C(k+l, l) C(p+q-k-l, q-l)
  ///  x_i^k x_{i+1}^{p-k} y_i^l y_{i+1}^{q-l}`.
  /// The sum is an integer computed exactly; only the final division
  /// rounds. Independent of the code under test (no quadrature).
  double
  steger_moment(const std::vector<Point> &vertices, const int p, const int q)
  {
    const auto power = [](const std::int64_t x, const int n) {
      std::int64_t r = 1;
      for (int i = 0; i < n; ++i)
        r *= x;
      return r;
    };
    std::int64_t      sum = 0;
    const std::size_t n   = vertices.size();
    for (std::size_t i = 0; i < n; ++i)
      {
        const Point       &a     = vertices[i];
        const Point       &b     = vertices[(i + 1) % n];
        const std::int64_t cross = a[0] * b[1] - b[0] * a[1];
        std::int64_t       inner = 0;
        for (int k = 0; k <= p; ++k)
          for (int l = 0; l <= q; ++l)
            inner += binomial(k + l, l) * binomial(p + q - k - l, q - l) *
                     power(a[0], k) * power(b[0], p - k) * power(a[1], l) *
                     power(b[1], q - l);
        sum += cross * inner;
      }
    return static_cast<double>(sum) * factorial(p) * factorial(q) /
           factorial(p + q + 2);
  }

  /// The integer polygon as a polygon of doubles.
  Poly
  to_polygon(const std::vector<Point> &vertices)
  {
    Poly polygon;
    for (const auto &v : vertices)
      polygon.push_back({{double(v[0]), double(v[1])}});
    return polygon;
  }

  /// All monomials x^a y^b with a + b <= 5, in the order (a, b) with b
  /// running fastest: 21 of them.
  template <typename T>
  std::array<T, 21>
  monomials(const mg::Point2D<T> &x)
  {
    std::array<T, 21> m;
    unsigned int      i = 0;
    for (int a = 0; a <= 5; ++a)
      for (int b = 0; a + b <= 5; ++b)
        m[i++] = std::pow(x[0], a) * std::pow(x[1], b);
    return m;
  }

  /// A polygon of doubles turned into one of Fad (no derivatives yet).
  std::vector<mg::Point2D<Fad>>
  to_fad(const Poly &polygon)
  {
    std::vector<mg::Point2D<Fad>> result;
    for (const auto &p : polygon)
      result.push_back({{Fad(p[0]), Fad(p[1])}});
    return result;
  }

  /// Whether two polygons have the same vertices in the same order, bit
  /// for bit (the degenerate cases promise the input's own vertices).
  bool
  same_vertices(const Poly &a, const Poly &b)
  {
    if (a.size() != b.size())
      return false;
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a[i][0] != b[i][0] || a[i][1] != b[i][1])
        return false;
    return true;
  }

  /// The unit square [0,1]^2, counter-clockwise.
  const Poly unit_square{{{0., 0.}}, {{1., 0.}}, {{1., 1.}}, {{0., 1.}}};
} // namespace

// R14.2, 2D segments: the overlap of [0,1] and [0.5,2] is [0.5,1];
// containment returns the inner interval; ends may come in either order;
// disjoint intervals and intervals that only touch (zero length, also when
// the touch is up to round-off: 0.1 + 0.2 is one ulp above 0.3) are empty.
TEST(MortarGeometry, IntervalOverlap)
{
  const auto partial = mg::overlap(0., 1., 0.5, 2.);
  EXPECT_TRUE(partial.non_empty);
  EXPECT_EQ(partial.begin, 0.5);
  EXPECT_EQ(partial.end, 1.);

  const auto contained = mg::overlap(0., 3., 1., 2.);
  EXPECT_TRUE(contained.non_empty);
  EXPECT_EQ(contained.begin, 1.);
  EXPECT_EQ(contained.end, 2.);

  const auto reversed = mg::overlap(1., 0., 2., 0.5);
  EXPECT_TRUE(reversed.non_empty);
  EXPECT_EQ(reversed.begin, 0.5);
  EXPECT_EQ(reversed.end, 1.);

  EXPECT_FALSE(mg::overlap(0., 1., 1., 2.).non_empty);
  EXPECT_FALSE(mg::overlap(0., 1., 2., 3.).non_empty);
  EXPECT_FALSE(mg::overlap(2., 3., 0., 1.).non_empty);
  ASSERT_GT(0.1 + 0.2, 0.3);
  EXPECT_FALSE(mg::overlap(0., 0.1 + 0.2, 0.3, 1.).non_empty);

  // The ends are the selected inputs with their derivatives.
  Fad        a0(2, 0, 0.), a1(2, 1, 1.);
  const auto with_derivatives = mg::overlap(a0, a1, Fad(0.5), Fad(2.));
  EXPECT_TRUE(with_derivatives.non_empty);
  EXPECT_EQ(with_derivatives.end.dx(1), 1.);
  EXPECT_EQ(with_derivatives.begin.dx(0), 0.);
  EXPECT_EQ(with_derivatives.begin.dx(1), 0.);
}

// R14.2: the triangle rules (deal.II's Witherden-Vincent rules) of the
// degrees mortar integration uses, 5 (7 points), 9 (19) and 13 (37), are
// positive rules with their points inside, and exact for their degree. On
// the reference triangle (0,0), (1,0), (0,1) (area 1/2) the integral of
// x^a y^b is a! b! / (a + b + 2)! (Dirichlet integral); every monomial of
// degree <= d must come out to 1e-13 relative. A rule of degree d cannot be
// exact for all of degree d + 1: at least one such monomial must miss by
// more than 1e-8 relative, which shows that the check tells degrees apart.
TEST(MortarGeometry, TriangleRulesAreExactForTheirDegree)
{
  for (const auto &[degree, size] :
       {std::pair<int, std::size_t>{5, 7}, {9, 19}, {13, 37}})
    {
      const auto &rule = mg::triangle_rule(degree);
      EXPECT_EQ(rule.size(), size) << "degree " << degree;
      double weight_sum = 0.;
      for (const auto &r : rule)
        {
          weight_sum += r.weight;
          EXPECT_GT(r.weight, 0.);
          EXPECT_NEAR(r.barycentric[0] + r.barycentric[1] + r.barycentric[2],
                      1.,
                      1e-15);
          for (const double b : r.barycentric)
            EXPECT_GT(b, 0.); // all points inside
        }
      EXPECT_NEAR(weight_sum, 1., 1e-14);

      const auto rule_integral = [&rule](const int a, const int b) {
        double sum = 0.;
        for (const auto &r : rule)
          // Barycentric (l0, l1, l2) of the vertices (0,0), (1,0), (0,1).
          sum += 0.5 * r.weight * std::pow(r.barycentric[1], a) *
                 std::pow(r.barycentric[2], b);
        return sum;
      };
      for (int a = 0; a <= degree; ++a)
        for (int b = 0; a + b <= degree; ++b)
          {
            const double exact =
              factorial(a) * factorial(b) / factorial(a + b + 2);
            EXPECT_NEAR(rule_integral(a, b), exact, 1e-13 * exact)
              << "degree " << degree << ": x^" << a << " y^" << b;
          }
      double worst_next = 0.;
      for (int a = 0; a <= degree + 1; ++a)
        {
          const double exact =
            factorial(a) * factorial(degree + 1 - a) / factorial(degree + 3);
          worst_next =
            std::max(worst_next,
                     std::abs(rule_integral(a, degree + 1 - a) - exact) /
                       exact);
        }
      EXPECT_GT(worst_next, 1e-8) << "degree " << degree;
    }
  EXPECT_EQ(&mg::triangle_rule(), &mg::triangle_rule(5));
  EXPECT_THROW(mg::triangle_rule(mg::max_triangle_rule_degree + 1),
               dealii::ExceptionBase);
}

// R14.2, R14.5: on a general (non-parallelogram) quadrilateral the shape
// functions are rational functions of the plane's coordinates (through the
// inverse bilinear map), so a polygon rule integrates them only
// approximately. The mortar code (mortar_3d.cc, rule_degree()) picks the
// rule by the quadrilateral's bilinear defect delta; this checks the error
// estimates it relies on. Quadrilateral: the unit square under a shear,
// one corner then moved by delta times its diagonal; the exact
// int N_k dA by a 4 x 4 Gauss rule in the parameters (N_k det J is a
// polynomial of degree 2 in each parameter there). The largest relative
// error over six directions of the move, measured (2026-12-03):
//   delta   degree 5  degree 7  degree 11  degree 13
//   0.002     2e-14
//   0.005     7e-13
//   0.03      1e-9      3e-14
//   0.05                7e-13
//   0.1       1e-7      5e-11     2e-15
//   0.15                          1e-13
//   0.2       4e-6      4e-9      5e-12      3e-13
//   0.3       3e-5      6e-8      2e-9       3e-10
// Checked: each rule within 1e-12 up to the largest delta for which
// rule_degree() picks it, and the next rule needed beyond;
// and that the image of the parameter square [0.5 - sigma/2, 0.5 +
// sigma/2]^2 fares like a whole facet with defect sigma delta.
TEST(MortarGeometry, ShapeFunctionIntegralsOnDistortedQuadrilaterals)
{
  const auto largest_error =
    [](const double delta, const unsigned int degree, const double sigma = 1.) {
      // The piece: the image of [lo, lo + sigma]^2 in the parameters.
      const double     lo = 0.5 - 0.5 * sigma;
      std::array<P, 4> v{{{{0., 0.}}, {{1., 0.2}}, {{0.3, 1.}}, {{1.3, 1.2}}}};
      const double     diagonal = std::hypot(1.3, 1.2);
      double           worst    = 0.;
      for (const double angle : {0., 1., 2., 3., 4., 5.})
        {
          auto w = v;
          w[3][0] += delta * diagonal * std::cos(angle);
          w[3][1] += delta * diagonal * std::sin(angle);
          const auto N = [](const P &xi) {
            return std::array<double, 4>{{(1. - xi[0]) * (1. - xi[1]),
                                          xi[0] * (1. - xi[1]),
                                          (1. - xi[0]) * xi[1],
                                          xi[0] * xi[1]}};
          };
          // Exact: Gauss in the parameters.
          std::array<double, 4> exact{{0., 0., 0., 0.}};
          const double          g[4]  = {0.5 - 0.5 * 0.8611363115940526,
                                         0.5 - 0.5 * 0.3399810435848563,
                                         0.5 + 0.5 * 0.3399810435848563,
                                         0.5 + 0.5 * 0.8611363115940526};
          const double          gw[4] = {0.5 * 0.3478548451374538,
                                         0.5 * 0.6521451548625461,
                                         0.5 * 0.6521451548625461,
                                         0.5 * 0.3478548451374538};
          for (unsigned int i = 0; i < 4; ++i)
            for (unsigned int j = 0; j < 4; ++j)
              {
                const double s = lo + sigma * g[i], t = lo + sigma * g[j];
                double       J[2][2];
                for (unsigned int d = 0; d < 2; ++d)
                  {
                    J[d][0] =
                      (1. - t) * (w[1][d] - w[0][d]) + t * (w[3][d] - w[2][d]);
                    J[d][1] =
                      (1. - s) * (w[2][d] - w[0][d]) + s * (w[3][d] - w[1][d]);
                  }
                const double det  = J[0][0] * J[1][1] - J[0][1] * J[1][0];
                const auto   n_st = N(P{{s, t}});
                for (unsigned int k = 0; k < 4; ++k)
                  exact[k] += sigma * sigma * gw[i] * gw[j] * det * n_st[k];
              }
          std::array<P, 4> piece;
          for (unsigned int c = 0; c < 4; ++c)
            piece[c] = mg::bilinear_map(
              w, P{{lo + sigma * (c % 2), lo + sigma * double(c / 2)}});
          const auto approximate = mg::integrate(
            mg::quadrilateral_polygon(piece),
            [&](const P &x) {
              const auto inverse = mg::inverse_bilinear_map(w, x);
              EXPECT_EQ(inverse.status, mg::InverseMapStatus::inside);
              return N(inverse.xi);
            },
            degree);
          for (unsigned int k = 0; k < 4; ++k)
            worst =
              std::max(worst, std::abs(approximate[k] - exact[k]) / exact[k]);
        }
      return worst;
    };
  EXPECT_LT(largest_error(0., 5), 1e-14);
  EXPECT_LT(largest_error(5e-3, 5), 1e-12);
  EXPECT_GT(largest_error(0.05, 5), 1e-10);
  EXPECT_LT(largest_error(0.05, 7), 1e-12);
  EXPECT_GT(largest_error(0.15, 7), 1e-10);
  EXPECT_LT(largest_error(0.15, 11), 1e-12);
  EXPECT_LT(largest_error(0.2, 13), 1e-12);
  // A piece of relative size sigma behaves like a whole facet with
  // sigma delta (bilinear_defect() in mortar_3d.cc relies on it).
  EXPECT_LT(largest_error(0.3, 11, 0.5), 1e-12);
  EXPECT_LT(largest_error(0.4, 7, 0.125), 1e-12);
  EXPECT_GT(largest_error(0.4, 7, 0.5), 1e-10);
}

// R14.2: Steger's exact moment formula (the reference of the next test)
// reproduces the closed forms it is compared with: the unit square
// (1/((a+1)(b+1))) and the triangle (0,0), (2,0), (0,3), the reference
// triangle stretched by 2 and 3 (2^(a+1) 3^(b+1) a! b! / (a+b+2)!). This
// keeps a typo in the reference formula from passing as a code error or
// hiding one.
TEST(MortarGeometry, ReferenceMomentFormulaMatchesClosedForms)
{
  const std::vector<Point> square{{{0, 0}}, {{1, 0}}, {{1, 1}}, {{0, 1}}};
  const std::vector<Point> triangle{{{0, 0}}, {{2, 0}}, {{0, 3}}};
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; a + b <= 5; ++b)
      {
        const double square_exact = 1. / ((a + 1) * (b + 1));
        EXPECT_NEAR(steger_moment(square, a, b),
                    square_exact,
                    1e-15 * square_exact);
        const double triangle_exact = std::pow(2., a + 1) *
                                      std::pow(3., b + 1) * factorial(a) *
                                      factorial(b) / factorial(a + b + 2);
        EXPECT_NEAR(steger_moment(triangle, a, b),
                    triangle_exact,
                    1e-15 * triangle_exact);
      }
}

// R14.2 ("a flat interface is integrated exactly"): integrate() is exact
// for every x^a y^b with a + b <= 5 over the unit square, the triangle
// (0,0), (2,0), (0,3), and the convex pentagon (1,0), (4,1), (5,4), (2,5),
// (0,2), against the closed forms of the previous test (Steger's formula
// for the pentagon), to 1e-13 relative. All integrands are positive on
// these polygons, so there is no cancellation to excuse a larger error.
// Clockwise input must give the same integrals. Both the array-valued and
// the scalar integrand are used.
TEST(MortarGeometry, MonomialIntegralsOverPolygonsAreExact)
{
  const std::vector<std::vector<Point>> polygons{
    {{{0, 0}}, {{1, 0}}, {{1, 1}}, {{0, 1}}},
    {{{0, 0}}, {{2, 0}}, {{0, 3}}},
    {{{1, 0}}, {{4, 1}}, {{5, 4}}, {{2, 5}}, {{0, 2}}}};
  for (const auto &vertices : polygons)
    {
      Poly polygon = to_polygon(vertices);
      ASSERT_TRUE(mg::is_convex(polygon));
      for (const bool clockwise : {false, true})
        {
          if (clockwise)
            std::reverse(polygon.begin(), polygon.end());
          const std::array<double, 21> integrals =
            mg::integrate(polygon, monomials<double>);
          unsigned int i = 0;
          for (int a = 0; a <= 5; ++a)
            for (int b = 0; a + b <= 5; ++b, ++i)
              {
                const double exact = steger_moment(vertices, a, b);
                EXPECT_NEAR(integrals[i], exact, 1e-13 * exact)
                  << "x^" << a << " y^" << b << " over " << vertices.size()
                  << " vertices, clockwise " << clockwise;
              }
          const double x2y3  = mg::integrate(polygon, [](const P &x) {
            return x[0] * x[0] * x[1] * x[1] * x[1];
          });
          const double exact = steger_moment(vertices, 2, 3);
          EXPECT_NEAR(x2y3, exact, 1e-13 * exact);
        }
    }
}

// R14.2: quadrature points of a polygon have weights that add up to its
// area, lie inside it, and an empty polygon (no overlap) has none; the
// area-weighted centroid of the pentagon equals its first moments over its
// area (Steger), and a triangle's centroid is the mean of its vertices.
TEST(MortarGeometry, AreaCentroidAndQuadraturePoints)
{
  const std::vector<Point> pentagon_vertices{
    {{1, 0}}, {{4, 1}}, {{5, 4}}, {{2, 5}}, {{0, 2}}};
  const Poly   pentagon = to_polygon(pentagon_vertices);
  const double area     = steger_moment(pentagon_vertices, 0, 0);
  EXPECT_DOUBLE_EQ(mg::signed_area(pentagon), area);
  Poly clockwise = pentagon;
  std::reverse(clockwise.begin(), clockwise.end());
  EXPECT_DOUBLE_EQ(mg::signed_area(clockwise), -area);
  EXPECT_DOUBLE_EQ(mg::area(clockwise), area);

  for (const Poly &p : {pentagon, clockwise})
    {
      const P c = mg::centroid(p);
      EXPECT_NEAR(c[0], steger_moment(pentagon_vertices, 1, 0) / area, 1e-14);
      EXPECT_NEAR(c[1], steger_moment(pentagon_vertices, 0, 1) / area, 1e-14);

      const auto points = mg::quadrature(p);
      EXPECT_EQ(points.size(), 7 * p.size());
      double sum = 0.;
      for (const auto &q : points)
        {
          EXPECT_GT(q.weight, 0.);
          sum += q.weight;
          EXPECT_TRUE(mg::internal::inside_or_on(pentagon, q.point, 0.));
        }
      EXPECT_NEAR(sum, area, 1e-14 * area);
    }

  const Poly triangle{{{0., 0.}}, {{3., 0.}}, {{1., 2.}}};
  const P    c = mg::centroid(triangle);
  EXPECT_NEAR(c[0], 4. / 3., 1e-15);
  EXPECT_NEAR(c[1], 2. / 3., 1e-15);

  EXPECT_TRUE(mg::quadrature(Poly{}).empty());
  EXPECT_EQ(mg::integrate(Poly{}, [](const P &) { return 1.; }), 0.);
}

// R14.2: is_convex() accepts convex polygons of either orientation and
// with collinear vertices (clipping leaves some), and refuses a re-entrant
// (arrow-shaped) polygon and a degenerate one.
TEST(MortarGeometry, Convexity)
{
  EXPECT_TRUE(mg::is_convex(unit_square));
  EXPECT_TRUE(mg::is_convex(
    Poly{{{0., 0.}}, {{0., 1.}}, {{1., 1.}}, {{1., 0.}}})); // clockwise
  EXPECT_TRUE(mg::is_convex(Poly{
    {{0., 0.}}, {{0.5, 0.}}, {{1., 0.}}, {{1., 1.}}, {{0., 1.}}})); // collinear
  EXPECT_FALSE(mg::is_convex(
    Poly{{{0., 0.}}, {{2., 1.}}, {{0., 2.}}, {{0.5, 1.}}})); // arrow
  EXPECT_FALSE(mg::is_convex(Poly{{{0., 0.}}, {{1., 0.}}, {{2., 0.}}}));
}

// R14.2: the square [-1,1]^2 clipped by the same square turned by 45
// degrees about its centre (vertices at distance sqrt 2 on the axes) is the
// regular octagon with inradius 1: four corner triangles with legs 2 - sqrt 2
// are cut off, area 4 - 2 (2 - sqrt 2)^2 = 8 (sqrt 2 - 1); its 8 vertices
// are at the circumradius sqrt(4 - 2 sqrt 2) (e.g. (1, sqrt 2 - 1)).
TEST(MortarGeometry, SquareAgainstRotatedSquareIsAnOctagon)
{
  const double s = std::sqrt(2.);
  const Poly   slave{{{-1., -1.}}, {{1., -1.}}, {{1., 1.}}, {{-1., 1.}}};
  const Poly   master{{{s, 0.}}, {{0., s}}, {{-s, 0.}}, {{0., -s}}};
  const Poly   octagon = mg::clip(slave, master);
  ASSERT_EQ(octagon.size(), 8u);
  EXPECT_NEAR(mg::signed_area(octagon), 8. * (s - 1.), 1e-14);
  for (const auto &p : octagon)
    EXPECT_NEAR(std::hypot(p[0], p[1]), std::sqrt(4. - 2. * s), 1e-14);
  EXPECT_TRUE(mg::is_convex(octagon));
  // The overlap does not depend on which facet is the slave.
  EXPECT_NEAR(mg::area(mg::clip(master, slave)), 8. * (s - 1.), 1e-14);
}

// R14.2: partial overlaps with areas by hand. The unit square against the
// triangle (0,0), (1.5,0), (0,1.5): the hypotenuse x + y = 1.5 cuts off the
// square's corner (1,1) with a triangle of legs 0.5, area 1 - 0.125 =
// 0.875, a pentagon. The unit square against [0.25,1.25] x [0.5,1.5]: the
// rectangle [0.25,1] x [0.5,1], area 0.75 x 0.5 = 0.375, centroid
// (0.625, 0.75).
TEST(MortarGeometry, PartialOverlapsHaveTheirAreasByHand)
{
  const Poly pentagon =
    mg::clip(unit_square, Poly{{{0., 0.}}, {{1.5, 0.}}, {{0., 1.5}}});
  EXPECT_EQ(pentagon.size(), 5u);
  EXPECT_NEAR(mg::signed_area(pentagon), 0.875, 1e-15);

  const Poly rectangle =
    mg::clip(unit_square,
             Poly{{{0.25, 0.5}}, {{1.25, 0.5}}, {{1.25, 1.5}}, {{0.25, 1.5}}});
  EXPECT_EQ(rectangle.size(), 4u);
  EXPECT_NEAR(mg::signed_area(rectangle), 0.375, 1e-15);
  const P c = mg::centroid(rectangle);
  EXPECT_NEAR(c[0], 0.625, 1e-15);
  EXPECT_NEAR(c[1], 0.75, 1e-15);
}

// R14.2, degenerate cases: a master that covers the slave gives the slave
// polygon itself (bit for bit), also when a slave vertex touches the
// master's boundary (the square's corner (1,1) lies on the hypotenuse of
// (0,0), (2,0), (0,2)); a slave that covers the master gives the master
// polygon itself; identical polygons give the slave polygon.
TEST(MortarGeometry, CoveringAndIdenticalPolygons)
{
  EXPECT_TRUE(same_vertices(
    mg::clip(unit_square, Poly{{{-1., -1.}}, {{4., -1.}}, {{-1., 4.}}}),
    unit_square));
  EXPECT_TRUE(same_vertices(mg::clip(unit_square,
                                     Poly{{{0., 0.}}, {{2., 0.}}, {{0., 2.}}}),
                            unit_square));

  const Poly small_triangle{{{0.2, 0.3}}, {{0.7, 0.4}}, {{0.4, 0.8}}};
  EXPECT_TRUE(
    same_vertices(mg::clip(unit_square, small_triangle), small_triangle));
  // ... also when the master touches the slave's boundary.
  const Poly touching_triangle{{{0., 0.}}, {{1., 0.5}}, {{0.5, 1.}}};
  EXPECT_TRUE(
    same_vertices(mg::clip(unit_square, touching_triangle), touching_triangle));

  EXPECT_TRUE(same_vertices(mg::clip(unit_square, unit_square), unit_square));
  // The same square starting at another vertex: still the whole square.
  const Poly shifted{{{1., 1.}}, {{0., 1.}}, {{0., 0.}}, {{1., 0.}}};
  const Poly same = mg::clip(unit_square, shifted);
  EXPECT_EQ(same.size(), 4u);
  EXPECT_DOUBLE_EQ(mg::signed_area(same), 1.);
}

// R14.2, degenerate cases: polygons that only touch along an edge or at a
// vertex, or that touch up to round-off, overlap in zero area and the
// result is empty; so are polygons that do not meet, including two
// triangles whose bounding boxes overlap (the master lies beyond the
// slave's hypotenuse x + y = 1, at x + y >= 1.2), where no shortcut on
// bounding boxes can decide.
TEST(MortarGeometry, TouchingAndSeparatePolygonsGiveNothing)
{
  EXPECT_TRUE(
    mg::clip(unit_square, Poly{{{1., 0.}}, {{2., 0.}}, {{2., 1.}}, {{1., 1.}}})
      .empty());
  EXPECT_TRUE(
    mg::clip(unit_square, Poly{{{1., 1.}}, {{2., 1.}}, {{2., 2.}}, {{1., 2.}}})
      .empty());
  const Poly lower{{{0., 0.}}, {{1., 0.}}, {{0., 1.}}};
  EXPECT_TRUE(
    mg::clip(lower, Poly{{{1., 1.}}, {{0., 1.}}, {{1., 0.}}}).empty());
  // Overlapping by 1e-15: a sliver of relative area 1e-15, below the
  // tolerance.
  const double e = 1e-15;
  EXPECT_TRUE(
    mg::clip(unit_square,
             Poly{{{1. - e, 0.}}, {{2., 0.}}, {{2., 1.}}, {{1. - e, 1.}}})
      .empty());
  EXPECT_TRUE(
    mg::clip(lower, Poly{{{1., 1.}}, {{0.6, 1.}}, {{1., 0.6}}}).empty());
  EXPECT_TRUE(
    mg::clip(unit_square, Poly{{{5., 5.}}, {{6., 5.}}, {{6., 6.}}, {{5., 6.}}})
      .empty());
  // A degenerate master (all vertices on a line) has no area to overlap.
  EXPECT_TRUE(
    mg::clip(unit_square, Poly{{{0., 0.}}, {{0.5, 0.5}}, {{1., 1.}}}).empty());
}

// R14.2, coincident vertices: the master is the upper-left half of the
// unit square, so three of its vertices coincide with slave vertices and
// two slave vertices lie on its diagonal edge. The overlap is that triangle,
// area 1/2, with exactly 3 vertices (no duplicates from intersections at
// the shared vertices). Perturbing the master by 1e-15 (below the merge
// tolerance) and repeating a slave vertex (also 1e-15 apart) must change
// neither the vertex count nor the area beyond round-off.
TEST(MortarGeometry, CoincidentVerticesAreMerged)
{
  const Poly master{{{0., 0.}}, {{1., 1.}}, {{0., 1.}}};
  const Poly triangle = mg::clip(unit_square, master);
  EXPECT_EQ(triangle.size(), 3u);
  EXPECT_DOUBLE_EQ(mg::signed_area(triangle), 0.5);

  const double e = 1e-15;
  const Poly   perturbed_master{{{e, -e}}, {{1. + e, 1. - e}}, {{-e, 1. + e}}};
  const Poly   repeated_vertex{
    {{0., 0.}}, {{1., 0.}}, {{1., 1.}}, {{1. + e, 1. - e}}, {{0., 1.}}};
  for (const Poly &slave : {unit_square, repeated_vertex})
    for (const Poly &m : {master, perturbed_master})
      {
        const Poly result = mg::clip(slave, m);
        EXPECT_EQ(result.size(), 3u);
        EXPECT_NEAR(mg::signed_area(result), 0.5, 1e-14);
      }

  // A repeated vertex in a partial overlap: the rectangle of
  // PartialOverlapsHaveTheirAreasByHand, still 4 vertices.
  const Poly rectangle =
    mg::clip(repeated_vertex,
             Poly{{{0.25, 0.5}}, {{1.25, 0.5}}, {{1.25, 1.5}}, {{0.25, 1.5}}});
  EXPECT_EQ(rectangle.size(), 4u);
  EXPECT_NEAR(mg::signed_area(rectangle), 0.375, 1e-15);
}

// R14.2, degenerate cases: slivers. The master's top is a roof over the
// slave's bottom edge y = 0: ridge (0.5, r), eaves (-1, e) and (2, e) with
// e < 0 < r. If the roof crosses y = 0 inside the slave, the true overlap is
// the triangle under the ridge, of half-base 1.5 r / (r - e) and area
// 1.5 r^2 / (r - e). The result is empty when that area is not above
// relative_tolerance (1e-12) times the smaller facet area (1): such a sliver
// carries no load and its segment map would be ill-conditioned.
// - r = 1e-13, e = -5e-13: area 2.5e-14, empty (its height is also below
//   the distance tolerance, so its vertices fall on the slave's edge);
// - r = 7e-12, e = -1e-10: area 6.9e-13, empty, although its vertices are
//   0.1 apart and its height is above the distance tolerance (3.6e-12):
//   only the area criterion removes it;
// - r = 2e-11, e = -1e-10: area 5e-12, kept, a triangle (its area has the
//   round-off of coordinates of size 1, 1e-16, relative to heights of
//   2e-11: checked to 1e-4).
// Raised to r = 1e-3 (e = -5e-13), the roof is above y = 0 all across the
// slave and the overlap is the pentagon under it: the roof height is linear
// from e at x = -1 to r at x = 0.5 and symmetric about x = 0.5, so the area
// is 2 int_0^0.5 h = e + 5 (r - e) / 6 = 5 r / 6 + e / 6.
TEST(MortarGeometry, SliversBelowTheToleranceAreEmpty)
{
  const auto roof = [](const double ridge, const double eave) {
    return Poly{
      {{-1., -1.}}, {{2., -1.}}, {{2., eave}}, {{0.5, ridge}}, {{-1., eave}}};
  };
  ASSERT_TRUE(mg::is_convex(roof(1e-3, -5e-13)));
  EXPECT_TRUE(mg::clip(unit_square, roof(1e-13, -5e-13)).empty());
  EXPECT_TRUE(mg::clip(unit_square, roof(7e-12, -1e-10)).empty());

  const Poly sliver = mg::clip(unit_square, roof(2e-11, -1e-10));
  EXPECT_EQ(sliver.size(), 3u);
  const double sliver_area = 1.5 * 2e-11 * 2e-11 / (2e-11 + 1e-10);
  EXPECT_NEAR(mg::area(sliver), sliver_area, 1e-4 * sliver_area);

  const Poly visible = mg::clip(unit_square, roof(1e-3, -5e-13));
  EXPECT_EQ(visible.size(), 5u);
  EXPECT_NEAR(mg::area(visible), 5. * 1e-3 / 6. - 5e-13 / 6., 1e-17);
}

// R14.2, degenerate cases: a slave vertex that lies on a master edge only
// up to round-off stays the slave's own vertex. The slave [-0.5,1]^2 and
// the master triangle (0,0), (2,0), (0,2) are turned together by ten
// different angles, so the slave corner (1,1) is on the master's
// hypotenuse in exact arithmetic but a few ulps to either side in floating
// point. The overlap is the unit square [0,1]^2 (area 1): its corner (1,1)
// must be the turned slave vertex bit for bit (not an intersection point
// recomputed from the master's edge), and with Sacado its derivatives with
// respect to the master coordinates must be exactly zero.
TEST(MortarGeometry, VertexOnAMasterEdgeStaysTheSlaves)
{
  for (unsigned int k = 1; k <= 10; ++k)
    {
      const double angle = 0.37 * k, c = std::cos(angle), s = std::sin(angle);
      const auto   turn = [c, s](const double x, const double y) {
        return P{{c * x - s * y, s * x + c * y}};
      };
      const Poly slave{turn(-0.5, -0.5),
                       turn(1., -0.5),
                       turn(1., 1.),
                       turn(-0.5, 1.)};
      const Poly master{turn(0., 0.), turn(2., 0.), turn(0., 2.)};
      const Poly result = mg::clip(slave, master);
      EXPECT_NEAR(mg::area(result), 1., 1e-14) << "angle " << angle;
      EXPECT_EQ(result.size(), 4u) << "angle " << angle;
      EXPECT_EQ(std::count(result.begin(), result.end(), slave[2]), 1)
        << "angle " << angle;

      auto slave_fad  = to_fad(slave);
      auto master_fad = to_fad(master);
      for (unsigned int v = 0; v < 3; ++v)
        for (unsigned int d = 0; d < 2; ++d)
          master_fad[v][d].diff(2 * v + d, 6);
      for (const auto &p : mg::clip(slave_fad, master_fad))
        if (p[0].val() == slave[2][0] && p[1].val() == slave[2][1])
          for (unsigned int k = 0; k < 6; ++k)
            {
              EXPECT_EQ(p[0].dx(k), 0.);
              EXPECT_EQ(p[1].dx(k), 0.);
            }
    }
}

// R14.2: orientation independence. The octagon case with clockwise slave,
// clockwise master or both gives the same area 8 (sqrt 2 - 1), and the
// result is always counter-clockwise (positive signed area). A clockwise
// unit square inside a clockwise triangle comes back as its own vertices in
// counter-clockwise order, area exactly 1.
TEST(MortarGeometry, OrientationDoesNotMatter)
{
  const double s = std::sqrt(2.);
  const Poly   slave{{{-1., -1.}}, {{1., -1.}}, {{1., 1.}}, {{-1., 1.}}};
  const Poly   master{{{s, 0.}}, {{0., s}}, {{-s, 0.}}, {{0., -s}}};
  Poly         slave_cw = slave, master_cw = master;
  std::reverse(slave_cw.begin(), slave_cw.end());
  std::reverse(master_cw.begin(), master_cw.end());
  for (const Poly &a : {slave, slave_cw})
    for (const Poly &b : {master, master_cw})
      EXPECT_NEAR(mg::signed_area(mg::clip(a, b)), 8. * (s - 1.), 1e-14);
  // Covering case with a clockwise slave: the slave's vertices,
  // counter-clockwise.
  Poly square_cw = unit_square;
  std::reverse(square_cw.begin(), square_cw.end());
  const Poly covered =
    mg::clip(square_cw, Poly{{{-1., -1.}}, {{-1., 4.}}, {{4., -1.}}});
  EXPECT_EQ(mg::signed_area(covered), 1.);
  Poly square_ccw = square_cw;
  std::reverse(square_ccw.begin(), square_ccw.end());
  EXPECT_TRUE(same_vertices(covered, square_ccw));
}

// R14.2 with R14.4: the clipped area and a polynomial integral over the
// clip polygon are differentiable. A generic configuration: a distorted
// square against a distorted turned square, every master edge cutting the
// slave, so every master and slave coordinate moves the overlap (checked:
// each derivative is larger than 1e-3). Sacado's derivative with respect to
// each of the 16 coordinates must match a central difference with step
// 1e-6 to 1e-7 relative (the difference's truncation error is about
// 1e-12, its round-off about 1e-10).
TEST(MortarGeometry, ClipAreaDerivativeMatchesFiniteDifferences)
{
  const Poly         slave{{{-1., -1.1}},
                   {{1.05, -0.95}},
                   {{0.97, 1.02}},
                   {{-1.03, 0.9}}};
  const Poly         master{{{1.45, 0.1}},
                    {{-0.05, 1.38}},
                    {{-1.4, -0.02}},
                    {{0.08, -1.43}}};
  const unsigned int n_coordinates = 16;
  const auto         quantities    = [](const auto &s, const auto &m) {
    using T            = std::decay_t<decltype(s[0][0])>;
    const auto polygon = mg::clip(s, m);
    const T    moment = mg::integrate(polygon, [](const mg::Point2D<T> &x) {
      return T(x[0] * x[0] * x[1] + 1.);
    });
    return std::array<T, 2>{{mg::area(polygon), moment}};
  };

  auto slave_fad  = to_fad(slave);
  auto master_fad = to_fad(master);
  for (unsigned int v = 0; v < 4; ++v)
    for (unsigned int d = 0; d < 2; ++d)
      {
        slave_fad[v][d].diff(2 * v + d, n_coordinates);
        master_fad[v][d].diff(8 + 2 * v + d, n_coordinates);
      }
  const auto with_derivatives = quantities(slave_fad, master_fad);
  ASSERT_EQ(mg::clip(slave, master).size(), 8u); // generic: an octagon

  const double h = 1e-6;
  for (unsigned int k = 0; k < n_coordinates; ++k)
    {
      Poly  plus_s = slave, minus_s = slave, plus_m = master, minus_m = master;
      Poly &plus  = k < 8 ? plus_s : plus_m;
      Poly &minus = k < 8 ? minus_s : minus_m;
      plus[(k % 8) / 2][k % 2] += h;
      minus[(k % 8) / 2][k % 2] -= h;
      const auto up   = quantities(plus_s, plus_m);
      const auto down = quantities(minus_s, minus_m);
      for (unsigned int q = 0; q < 2; ++q)
        {
          const double difference = (up[q] - down[q]) / (2. * h);
          const double derivative = with_derivatives[q].dx(k);
          EXPECT_GT(std::abs(difference), 1e-3) << "coordinate " << k;
          EXPECT_NEAR(derivative, difference, 1e-7 * std::abs(difference))
            << "quantity " << q << ", coordinate " << k;
        }
    }
}

// R14.2: projection onto the auxiliary plane and back. make_plane() gives
// an orthonormal right-handed frame (e1, e2, n); a point of the plane goes
// to 2D and back unchanged; a point at height h along the normal projects
// to the same 2D point, and height_above() returns h. Right-handedness
// matters for orientation: the triangle (0,0,0), (1,0,0), (0,1,0) is
// counter-clockwise seen from +z, so in the plane with normal +z its
// signed area is +1/2, with normal -z it is -1/2. And a unit square in a
// plane tilted by 30 degrees about x projects onto the xy-plane with area
// cos 30 degrees.
TEST(MortarGeometry, ProjectionOntoAPlaneAndBack)
{
  using P3          = mg::Point3D<double>;
  const P3   center = {{0.3, -0.2, 1.1}};
  const P3   normal = {{1. / 3., 2. / 3., 2. / 3.}};
  const auto plane  = mg::make_plane(center, normal);
  const auto dot    = [](const P3 &a, const P3 &b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  EXPECT_NEAR(dot(plane.e1, plane.e1), 1., 1e-15);
  EXPECT_NEAR(dot(plane.e2, plane.e2), 1., 1e-15);
  EXPECT_NEAR(dot(plane.e1, plane.e2), 0., 1e-15);
  EXPECT_NEAR(dot(plane.e1, normal), 0., 1e-15);
  EXPECT_NEAR(dot(plane.e2, normal), 0., 1e-15);
  // (e1 x e2) . n = 1: right-handed.
  const P3 e1_x_e2 = {{plane.e1[1] * plane.e2[2] - plane.e1[2] * plane.e2[1],
                       plane.e1[2] * plane.e2[0] - plane.e1[0] * plane.e2[2],
                       plane.e1[0] * plane.e2[1] - plane.e1[1] * plane.e2[0]}};
  EXPECT_NEAR(dot(e1_x_e2, normal), 1., 1e-15);

  const P  p          = {{0.7, -1.3}};
  const P3 in_plane   = mg::from_plane(plane, p);
  const P  round_trip = mg::to_plane(plane, in_plane);
  EXPECT_NEAR(round_trip[0], p[0], 1e-15);
  EXPECT_NEAR(round_trip[1], p[1], 1e-15);
  EXPECT_NEAR(mg::height_above(plane, in_plane), 0., 1e-15);
  const double h     = 0.45;
  const P3     above = {{in_plane[0] + h * normal[0],
                         in_plane[1] + h * normal[1],
                         in_plane[2] + h * normal[2]}};
  const P      foot  = mg::to_plane(plane, above);
  EXPECT_NEAR(foot[0], p[0], 1e-15);
  EXPECT_NEAR(foot[1], p[1], 1e-15);
  EXPECT_NEAR(mg::height_above(plane, above), h, 1e-15);

  const std::vector<P3> triangle{{{0., 0., 0.}},
                                 {{1., 0., 0.}},
                                 {{0., 1., 0.}}};
  for (const double nz : {1., -1.})
    {
      const auto xy = mg::make_plane(P3{{0., 0., 0.}}, P3{{0., 0., nz}});
      Poly       projected;
      for (const auto &x : triangle)
        projected.push_back(mg::to_plane(xy, x));
      EXPECT_NEAR(mg::signed_area(projected), 0.5 * nz, 1e-15);
    }

  const double c = std::sqrt(3.) / 2., s = 0.5;
  const auto   xy = mg::make_plane(P3{{0., 0., 0.}}, P3{{0., 0., 1.}});
  Poly         tilted;
  for (const auto &q :
       std::vector<P>{{{0., 0.}}, {{1., 0.}}, {{1., 1.}}, {{0., 1.}}})
    tilted.push_back(mg::to_plane(xy, P3{{q[0], c * q[1], s * q[1]}}));
  EXPECT_NEAR(mg::area(tilted), c, 1e-15);
}

// R14.2: deal.II's lexicographic vertex order 0:(0,0), 1:(1,0), 2:(0,1),
// 3:(1,1) goes around the facet as 0, 1, 3, 2. Taken in lexicographic
// order, the unit square is a bow tie of signed area 0; in polygon order it
// is the counter-clockwise square of area 1. For a distorted quadrilateral
// the polygon's area must equal the integral of the bilinear map's
// Jacobian determinant over [0,1]^2 (bilinear in s, t, so the 2x2 Gauss
// rule is exact): an independent computation.
TEST(MortarGeometry, PolygonOrderOfLexicographicVertices)
{
  constexpr auto order = mg::polygon_order_of_quadrilateral();
  EXPECT_EQ(order, (std::array<unsigned int, 4>{{0, 1, 3, 2}}));

  const std::array<P, 4> square{
    {{{0., 0.}}, {{1., 0.}}, {{0., 1.}}, {{1., 1.}}}};
  EXPECT_EQ(mg::signed_area(Poly(square.begin(), square.end())), 0.);
  EXPECT_EQ(mg::signed_area(mg::quadrilateral_polygon(square)), 1.);

  const std::array<P, 4> v{
    {{{0., 0.}}, {{2., 0.3}}, {{0.4, 1.7}}, {{2.5, 2.2}}}};
  double       jacobian_integral = 0.;
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.), 0.5 + 0.5 / std::sqrt(3.)};
  for (const double s : g)
    for (const double t : g)
      {
        double J[2][2];
        for (unsigned int d = 0; d < 2; ++d)
          {
            J[d][0] = (1. - t) * (v[1][d] - v[0][d]) + t * (v[3][d] - v[2][d]);
            J[d][1] = (1. - s) * (v[2][d] - v[0][d]) + s * (v[3][d] - v[1][d]);
          }
        jacobian_integral += 0.25 * (J[0][0] * J[1][1] - J[0][1] * J[1][0]);
      }
  EXPECT_NEAR(mg::signed_area(mg::quadrilateral_polygon(v)),
              jacobian_integral,
              1e-14);
}

// R14.2: the inverse bilinear map on a distorted quadrilateral (lexicographic
// vertices (0,0), (2,0.3), (0.4,1.7), (2.5,2.2)). Round trip: parameters on
// a 5 x 5 grid of [0,1]^2 (corners included) are mapped forward and back
// to 1e-12, status inside. A point mapped from (1.3, 0.5) is found at those
// parameters but reported outside; a collapsed element (all vertices on one
// line) is singular. The derivative of the parameters with respect to the
// point (Sacado, through the final Newton step) must match central
// differences of the double inverse map to 1e-7 relative: it is the
// inverse of the map's Jacobian.
TEST(MortarGeometry, InverseBilinearMapRoundTrip)
{
  const std::array<P, 4> v{
    {{{0., 0.}}, {{2., 0.3}}, {{0.4, 1.7}}, {{2.5, 2.2}}}};
  for (unsigned int i = 0; i <= 4; ++i)
    for (unsigned int j = 0; j <= 4; ++j)
      {
        const P    xi      = {{0.25 * i, 0.25 * j}};
        const P    x       = mg::bilinear_map(v, xi);
        const auto inverse = mg::inverse_bilinear_map(v, x);
        EXPECT_EQ(inverse.status, mg::InverseMapStatus::inside);
        EXPECT_NEAR(inverse.xi[0], xi[0], 1e-12);
        EXPECT_NEAR(inverse.xi[1], xi[1], 1e-12);
        EXPECT_LE(inverse.iterations, mg::max_newton_iterations);
      }

  const auto outside =
    mg::inverse_bilinear_map(v, mg::bilinear_map(v, P{{1.3, 0.5}}));
  EXPECT_EQ(outside.status, mg::InverseMapStatus::outside);
  EXPECT_NEAR(outside.xi[0], 1.3, 1e-12);
  EXPECT_NEAR(outside.xi[1], 0.5, 1e-12);

  const std::array<P, 4> collapsed{
    {{{0., 0.}}, {{1., 1.}}, {{2., 2.}}, {{3., 3.}}}};
  EXPECT_EQ(mg::inverse_bilinear_map(collapsed, P{{0.5, 0.5}}).status,
            mg::InverseMapStatus::singular);

  std::array<mg::Point2D<Fad>, 4> v_fad;
  for (unsigned int i = 0; i < 4; ++i)
    v_fad[i] = {{Fad(v[i][0]), Fad(v[i][1])}};
  const P                x0 = mg::bilinear_map(v, P{{0.35, 0.6}});
  const mg::Point2D<Fad> x_fad{{Fad(2, 0, x0[0]), Fad(2, 1, x0[1])}};
  const auto with_derivatives = mg::inverse_bilinear_map(v_fad, x_fad);
  ASSERT_EQ(with_derivatives.status, mg::InverseMapStatus::inside);
  const double h = 1e-6;
  for (unsigned int k = 0; k < 2; ++k)
    {
      P plus = x0, minus = x0;
      plus[k] += h;
      minus[k] -= h;
      const auto up   = mg::inverse_bilinear_map(v, plus);
      const auto down = mg::inverse_bilinear_map(v, minus);
      for (unsigned int d = 0; d < 2; ++d)
        {
          const double difference = (up.xi[d] - down.xi[d]) / (2. * h);
          EXPECT_NEAR(with_derivatives.xi[d].dx(k),
                      difference,
                      1e-7 * std::abs(difference));
        }
    }
}

// R14.2: the inverse of the linear triangle map is a linear solve. Round
// trip for parameters inside the triangle (0.1,0.2), (1.9,0.5), (0.6,1.4)
// to 1e-14; the parameters (0.7, 0.6) (sum 1.3 > 1) are found but reported
// outside; a triangle with collinear vertices is singular.
TEST(MortarGeometry, InverseBilinearMapAtTheRoundOffFloor)
{
  // A facet 1e-4 across at coordinates of 1000: the parameter of a point
  // is known only to about 1e-16 * 1000 / 1e-4 = 1e-9, so Newton's step
  // stalls far above the step tolerance (1e-13). That floor counts as
  // converged (mg::newton_stalled()); before, such maps "did not converge"
  // and mortar dropped their quadrature points at random (2D ironing with
  // mortar stalled that way). The answer is right to the floor.
  const double           h = 1e-4, c = 1000.;
  const std::array<P, 4> v{{{{c, c}},
                            {{c + h, c + 0.1 * h}},
                            {{c + 0.2 * h, c + h}},
                            {{c + 1.1 * h, c + 1.3 * h}}}};
  for (const P &xi : {P{{0.3, 0.6}}, P{{0.9, 0.1}}})
    {
      const auto inverse = mg::inverse_bilinear_map(v, mg::bilinear_map(v, xi));
      EXPECT_EQ(inverse.status, mg::InverseMapStatus::inside);
      EXPECT_NEAR(inverse.xi[0], xi[0], 1e-7);
      EXPECT_NEAR(inverse.xi[1], xi[1], 1e-7);
    }
  // Newton that still converges is never taken for stalled.
  EXPECT_FALSE(mg::newton_stalled(1e-9, 1e-4));
  EXPECT_FALSE(mg::newton_stalled(1e-12, 1e-6));
  EXPECT_TRUE(mg::newton_stalled(2e-14, 3e-14));
  EXPECT_FALSE(mg::newton_stalled(1e-7, 1e-7));
}

TEST(MortarGeometry, InverseTriangleMapRoundTrip)
{
  const std::array<P, 3> v{{{{0.1, 0.2}}, {{1.9, 0.5}}, {{0.6, 1.4}}}};
  for (const P &xi :
       {P{{0., 0.}}, P{{1., 0.}}, P{{0., 1.}}, P{{0.2, 0.3}}, P{{0.5, 0.5}}})
    {
      const auto inverse = mg::inverse_triangle_map(v, mg::triangle_map(v, xi));
      EXPECT_EQ(inverse.status, mg::InverseMapStatus::inside);
      EXPECT_NEAR(inverse.xi[0], xi[0], 1e-14);
      EXPECT_NEAR(inverse.xi[1], xi[1], 1e-14);
    }
  const auto outside =
    mg::inverse_triangle_map(v, mg::triangle_map(v, P{{0.7, 0.6}}));
  EXPECT_EQ(outside.status, mg::InverseMapStatus::outside);
  EXPECT_NEAR(outside.xi[0], 0.7, 1e-14);
  EXPECT_NEAR(outside.xi[1], 0.6, 1e-14);

  const std::array<P, 3> collinear{{{{0., 0.}}, {{1., 1.}}, {{3., 3.}}}};
  EXPECT_EQ(mg::inverse_triangle_map(collinear, P{{0.5, 0.5}}).status,
            mg::InverseMapStatus::singular);
}
