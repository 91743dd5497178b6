#pragma once

/// @file
/// Geometry of mortar segment integration (R14.2): the overlap of two
/// parameter intervals in 2D, and in 3D the clipping of a master facet
/// against a slave facet in the slave facet's auxiliary plane (Puso and
/// Laursen 2004; Popp, Gitterle, Gee and Wall 2010), the areas, centroids
/// and quadrature of the resulting convex polygons, and the inverse maps
/// from the plane back to facet parameters.
///
/// Everything is templated on the scalar type @p T and works with `double`
/// and with `Sacado::Fad::DFad<double>`, so that the mortar linearization
/// (R14.4) can differentiate the segments and polygons. Decisions (inside or
/// outside an edge, merge two vertices or not, empty or not) are taken on
/// the values only (value()); the arithmetic that produces the returned
/// coordinates, areas and weights is done in @p T, so for a generic
/// (non-degenerate) configuration the derivatives are those of the exact
/// geometry. No function calls a `std::` math function on @p T directly:
/// `using std::sqrt; sqrt(x)` lets argument-dependent lookup pick Sacado's
/// overloads.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <Sacado.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace glide
{
  namespace mortar_geometry
  {
    /// A point (or vector) of a plane: two coordinates.
    template <typename T>
    using Point2D = std::array<T, 2>;

    /// A point (or vector) in space.
    template <typename T>
    using Point3D = std::array<T, 3>;

    /// A polygon of the plane: its vertices in order around it (either
    /// orientation on input; the functions that return polygons return them
    /// counter-clockwise). The last vertex connects back to the first, it is
    /// not repeated.
    template <typename T>
    using Polygon = std::vector<Point2D<T>>;

    /// Vertices closer than this fraction of the size of the polygons
    /// involved (the diagonal of their common bounding box) are one vertex,
    /// and a vertex closer than it to a master edge's line is on that line.
    /// Why 1e-12: the clipping arithmetic loses a few digits at most
    /// (round-off of about 1e-15 relative), so genuinely coincident vertices
    /// that come out of different computations (a master node projected onto
    /// a slave node's position) differ by much less; and no mesh has features
    /// a trillion times smaller than its facets.
    inline constexpr double relative_tolerance = 1e-12;

    /// The value of @p x without its derivatives: the number that decisions
    /// are taken on. For `double` it is @p x itself.
    template <typename T>
    double
    value(const T &x)
    {
      return Sacado::ScalarValue<T>::eval(x);
    }

    /// The value of each coordinate of @p p.
    template <typename T, std::size_t n>
    std::array<double, n>
    value(const std::array<T, n> &p)
    {
      std::array<double, n> v;
      for (std::size_t i = 0; i < n; ++i)
        v[i] = value(p[i]);
      return v;
    }

    // ------------------------------------------------------------------
    // 2D: overlap of parameter intervals
    // ------------------------------------------------------------------

    /// The overlap of two parameter intervals: [begin, end] if non_empty.
    template <typename T>
    struct Interval
    {
      /// Start of the overlap (the larger of the two lower ends).
      T begin;
      /// End of the overlap (the smaller of the two upper ends).
      T end;
      /// Whether the overlap has positive length. Touching intervals
      /// (`end == begin`) have none: a mortar segment of zero length
      /// contributes nothing and only brings a singular segment map.
      bool non_empty;
    };

    /// Overlap of the intervals with ends @p a0, @p a1 and @p b0, @p b1
    /// (2D segment-based mortar integration: the slave element's parameter
    /// range against the range covered by a projected master element). The
    /// ends of each interval may come in either order. The overlap is empty
    /// if its length is not larger than relative_tolerance times the longer
    /// interval, so that intervals that touch up to round-off are reported
    /// as touching. The returned ends are copies of the inputs (min and max
    /// select, they do not compute), so their derivatives are those of the
    /// selected ends.
    template <typename T>
    Interval<T>
    overlap(const T &a0, const T &a1, const T &b0, const T &b1)
    {
      const T &a_low  = value(a0) <= value(a1) ? a0 : a1;
      const T &a_high = value(a0) <= value(a1) ? a1 : a0;
      const T &b_low  = value(b0) <= value(b1) ? b0 : b1;
      const T &b_high = value(b0) <= value(b1) ? b1 : b0;

      Interval<T> result{value(a_low) >= value(b_low) ? a_low : b_low,
                         value(a_high) <= value(b_high) ? a_high : b_high,
                         false};
      const double longer =
        std::max(value(a_high) - value(a_low), value(b_high) - value(b_low));
      result.non_empty =
        value(result.end) - value(result.begin) > relative_tolerance * longer;
      return result;
    }

    // ------------------------------------------------------------------
    // Projection onto a plane and back
    // ------------------------------------------------------------------

    /// A plane in space with an orthonormal frame: the slave facet's
    /// auxiliary plane of 3D mortar integration.
    template <typename T>
    struct Plane
    {
      /// A point of the plane: the origin of the 2D coordinates.
      Point3D<T> center;
      /// Unit normal.
      Point3D<T> normal;
      /// First in-plane unit vector (the 2D x axis).
      Point3D<T> e1;
      /// Second in-plane unit vector (the 2D y axis), `normal x e1`, so that
      /// counter-clockwise in 2D is counter-clockwise seen from the side the
      /// normal points to.
      Point3D<T> e2;
    };

    /// The plane through @p center with the unit normal @p normal and an
    /// in-plane frame built from it: `e1` is the normalized component of the
    /// coordinate axis least aligned with the normal (so never a poorly
    /// conditioned direction), `e2 = normal x e1`. The choice of axis is a
    /// branch, but a frame is only ever used as a whole: a polygon's area
    /// and integrals do not depend on which in-plane frame is used.
    template <typename T>
    Plane<T>
    make_plane(const Point3D<T> &center, const Point3D<T> &normal)
    {
      using std::sqrt;
      std::size_t axis = 0;
      for (std::size_t d = 1; d < 3; ++d)
        if (std::abs(value(normal[d])) < std::abs(value(normal[axis])))
          axis = d;
      Plane<T> plane{center, normal, {}, {}};
      // e1 = axis - (axis . n) n, normalized.
      for (std::size_t d = 0; d < 3; ++d)
        plane.e1[d] = -normal[axis] * normal[d];
      plane.e1[axis] += 1.;
      const T length =
        sqrt(plane.e1[0] * plane.e1[0] + plane.e1[1] * plane.e1[1] +
             plane.e1[2] * plane.e1[2]);
      for (auto &x : plane.e1)
        x /= length;
      plane.e2 = {{normal[1] * plane.e1[2] - normal[2] * plane.e1[1],
                   normal[2] * plane.e1[0] - normal[0] * plane.e1[2],
                   normal[0] * plane.e1[1] - normal[1] * plane.e1[0]}};
      return plane;
    }

    /// The 2D coordinates `((x - center) . e1, (x - center) . e2)` of the
    /// orthogonal projection of @p x onto @p plane (the projection along
    /// the plane's normal, as Puso and Laursen project the master facet onto
    /// the slave facet's auxiliary plane).
    template <typename T>
    Point2D<T>
    to_plane(const Plane<T> &plane, const Point3D<T> &x)
    {
      Point2D<T> p{{T(0.), T(0.)}};
      for (std::size_t d = 0; d < 3; ++d)
        {
          const T relative = x[d] - plane.center[d];
          p[0] += relative * plane.e1[d];
          p[1] += relative * plane.e2[d];
        }
      return p;
    }

    /// The signed distance `(x - center) . normal` of @p x from @p plane:
    /// the part of @p x that to_plane() drops.
    template <typename T>
    T
    height_above(const Plane<T> &plane, const Point3D<T> &x)
    {
      T h = 0.;
      for (std::size_t d = 0; d < 3; ++d)
        h += (x[d] - plane.center[d]) * plane.normal[d];
      return h;
    }

    /// The point of space `center + p[0] e1 + p[1] e2` with 2D coordinates
    /// @p p in @p plane: the inverse of to_plane() for points of the plane.
    template <typename T>
    Point3D<T>
    from_plane(const Plane<T> &plane, const Point2D<T> &p)
    {
      Point3D<T> x;
      for (std::size_t d = 0; d < 3; ++d)
        x[d] = plane.center[d] + p[0] * plane.e1[d] + p[1] * plane.e2[d];
      return x;
    }

    // ------------------------------------------------------------------
    // Polygons: area, centroid, orientation, convexity
    // ------------------------------------------------------------------

    /// Signed area of @p polygon by the shoelace formula
    /// `A = 1/2 sum_i (x_i y_{i+1} - x_{i+1} y_i)`: positive if the vertices
    /// go counter-clockwise. Zero for fewer than three vertices.
    template <typename T>
    T
    signed_area(const Polygon<T> &polygon)
    {
      T                 twice_area = 0.;
      const std::size_t n          = polygon.size();
      if (n < 3)
        return twice_area;
      for (std::size_t i = 0; i < n; ++i)
        {
          const Point2D<T> &p = polygon[i];
          const Point2D<T> &q = polygon[(i + 1) % n];
          twice_area += p[0] * q[1] - q[0] * p[1];
        }
      return 0.5 * twice_area;
    }

    /// Area of @p polygon, whatever its orientation.
    template <typename T>
    T
    area(const Polygon<T> &polygon)
    {
      using std::abs;
      return abs(signed_area(polygon));
    }

    /// Mean of the vertices of @p polygon (not its centroid unless it is a
    /// triangle or symmetric): the point the polygon is split into triangles
    /// from. It lies inside any convex polygon and, unlike the centroid,
    /// needs no division by the area, so it stays defined and smooth as a
    /// polygon degenerates.
    template <typename T>
    Point2D<T>
    vertex_mean(const Polygon<T> &polygon)
    {
      Point2D<T> mean{{T(0.), T(0.)}};
      for (const auto &p : polygon)
        {
          mean[0] += p[0];
          mean[1] += p[1];
        }
      const double n = polygon.size();
      mean[0] /= n;
      mean[1] /= n;
      return mean;
    }

    /// Centroid (centre of area) of @p polygon,
    /// `c = 1/(6A) sum_i (p_i + p_{i+1}) (x_i y_{i+1} - x_{i+1} y_i)`,
    /// either orientation. A polygon of zero area has no centre of area: its
    /// vertex_mean() is returned instead.
    template <typename T>
    Point2D<T>
    centroid(const Polygon<T> &polygon)
    {
      const T a = signed_area(polygon);
      if (value(a) == 0.)
        return polygon.empty() ? Point2D<T>{{T(0.), T(0.)}} :
                                 vertex_mean(polygon);
      Point2D<T>        c{{T(0.), T(0.)}};
      const std::size_t n = polygon.size();
      for (std::size_t i = 0; i < n; ++i)
        {
          const Point2D<T> &p     = polygon[i];
          const Point2D<T> &q     = polygon[(i + 1) % n];
          const T           cross = p[0] * q[1] - q[0] * p[1];
          c[0] += (p[0] + q[0]) * cross;
          c[1] += (p[1] + q[1]) * cross;
        }
      c[0] /= 6. * a;
      c[1] /= 6. * a;
      return c;
    }

    /// The diagonal of the bounding box of @p a and @p b together: the
    /// length scale of the tolerances (relative_tolerance).
    template <typename T>
    double
    size(const Polygon<T> &a, const Polygon<T> &b = {})
    {
      if (a.empty() && b.empty())
        return 0.;
      double low[2]  = {std::numeric_limits<double>::max(),
                        std::numeric_limits<double>::max()};
      double high[2] = {std::numeric_limits<double>::lowest(),
                        std::numeric_limits<double>::lowest()};
      for (const Polygon<T> *polygon : {&a, &b})
        for (const auto &p : *polygon)
          for (unsigned int d = 0; d < 2; ++d)
            {
              low[d]  = std::min(low[d], value(p[d]));
              high[d] = std::max(high[d], value(p[d]));
            }
      return std::hypot(high[0] - low[0], high[1] - low[1]);
    }

    /// @p polygon without repeated vertices: a vertex closer than
    /// @p distance to the vertex kept before it (cyclically, so the last
    /// against the first too) is dropped, the earlier one stays with its
    /// derivatives.
    template <typename T>
    Polygon<T>
    merge_coincident_vertices(const Polygon<T> &polygon, const double distance)
    {
      Polygon<T> merged;
      merged.reserve(polygon.size());
      const auto close = [distance](const Point2D<T> &p, const Point2D<T> &q) {
        return std::hypot(value(p[0]) - value(q[0]),
                          value(p[1]) - value(q[1])) <= distance;
      };
      for (const auto &p : polygon)
        if (merged.empty() || !close(merged.back(), p))
          merged.push_back(p);
      while (merged.size() > 1 && close(merged.back(), merged.front()))
        merged.pop_back();
      return merged;
    }

    /// @p polygon in counter-clockwise order (reversed if its signed area is
    /// negative).
    template <typename T>
    Polygon<T>
    counter_clockwise(const Polygon<T> &polygon)
    {
      Polygon<T> result = polygon;
      if (value(signed_area(polygon)) < 0.)
        std::reverse(result.begin(), result.end());
      return result;
    }

    /// Whether @p polygon is convex (either orientation): every turn from
    /// one edge to the next goes the same way. Turns smaller than
    /// relative_tolerance (collinear vertices, as clipping leaves them) do
    /// not count; a polygon with fewer than three vertices or no area is
    /// not convex. Callers check the projected facets with this before
    /// clip(), which needs a convex master.
    template <typename T>
    bool
    is_convex(const Polygon<T> &polygon)
    {
      const std::size_t n = polygon.size();
      if (n < 3)
        return false;
      const double scale = size(polygon);
      if (scale == 0.)
        return false;
      int sign = 0;
      for (std::size_t i = 0; i < n; ++i)
        {
          const auto   p = value(polygon[i]);
          const auto   q = value(polygon[(i + 1) % n]);
          const auto   r = value(polygon[(i + 2) % n]);
          const double turn =
            (q[0] - p[0]) * (r[1] - q[1]) - (q[1] - p[1]) * (r[0] - q[0]);
          if (std::abs(turn) <= relative_tolerance * scale * scale)
            continue;
          const int this_sign = turn > 0. ? 1 : -1;
          if (sign != 0 && this_sign != sign)
            return false;
          sign = this_sign;
        }
      return sign != 0;
    }

    // ------------------------------------------------------------------
    // Clipping (3D mortar segments)
    // ------------------------------------------------------------------

    namespace internal
    {
      /// Whether @p p lies inside the convex counter-clockwise polygon
      /// @p convex or within @p distance of its boundary's edge lines (on
      /// values).
      template <typename T>
      bool
      inside_or_on(const Polygon<T> &convex,
                   const Point2D<T> &p,
                   const double      distance)
      {
        const std::size_t n = convex.size();
        const auto        x = value(p);
        for (std::size_t e = 0; e < n; ++e)
          {
            const auto   a = value(convex[e]);
            const auto   b = value(convex[(e + 1) % n]);
            const double cross =
              (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]);
            if (cross < -distance * std::hypot(b[0] - a[0], b[1] - a[1]))
              return false;
          }
        return true;
      }
    } // namespace internal

    /// The overlap of the slave polygon @p slave and the master polygon
    /// @p master, both in the slave facet's auxiliary plane: the polygon
    /// over which one slave-master pair of facets is integrated in 3D
    /// (R14.2), counter-clockwise, or empty if the facets do not overlap.
    ///
    /// Method: Sutherland-Hodgman. The slave polygon is cut by the half-plane
    /// on the inner side of each master edge in turn. Both inputs may come in
    /// either orientation (each is made counter-clockwise first), and
    /// vertices closer than relative_tolerance x size() are merged first.
    ///
    /// Assumption: the facets are convex after projection (bilinear faces
    /// that are not strongly warped and triangles are). The intersection of
    /// two convex polygons is convex, so the result can be integrated by
    /// quadrature() and integrate(). If the master is not convex, the result
    /// is the part of the slave inside the half-planes of all master edges:
    /// a subset of the true overlap that misses the region near each
    /// re-entrant corner, i.e. the overlap area is underestimated. A
    /// non-convex slave gives the right area, but the result may then be
    /// non-convex (or pieces joined by zero-width bridges) and the centroid
    /// fan of quadrature() is no longer valid. Check with is_convex().
    ///
    /// Degenerate cases, all decided on values with the tolerance above:
    /// - a slave vertex on a master edge's line counts as inside that edge,
    ///   and no intersection point is computed for an edge that starts or ends
    ///   on the line (so none is computed twice or from a tiny denominator);
    ///   intersection points are computed only between a vertex strictly
    ///   inside and one strictly outside;
    /// - master covering the slave (all slave vertices inside or on): the
    ///   result is the slave polygon, its own vertices (counter-clockwise,
    ///   coincident ones merged); identical polygons are such a case;
    /// - slave covering the master: the result is the master polygon, its
    ///   own vertices (with their derivatives, none with respect to the
    ///   slave);
    /// - touching edges or vertices, and no overlap: a result of fewer than
    ///   three vertices, or of area not larger than relative_tolerance times
    ///   the smaller input area, is empty.
    ///
    /// Derivatives (T a Sacado type): the intersection points are
    /// `p + t (q - p)`, `t = d_p / (d_p - d_q)` with `d` the cross product of
    /// the master edge with the vector to the vertex, computed in T; so in a
    /// generic configuration the result's vertices, area and quadrature
    /// points carry the exact derivatives with respect to the slave and
    /// master coordinates.
    template <typename T>
    Polygon<T>
    clip(const Polygon<T> &slave, const Polygon<T> &master)
    {
      const double     scale    = size(slave, master);
      const double     distance = relative_tolerance * scale;
      const Polygon<T> subject =
        counter_clockwise(merge_coincident_vertices(slave, distance));
      const Polygon<T> clipper =
        counter_clockwise(merge_coincident_vertices(master, distance));
      const double subject_area = std::abs(value(signed_area(subject)));
      const double clipper_area = std::abs(value(signed_area(clipper)));
      if (subject.size() < 3 || clipper.size() < 3 || scale == 0. ||
          subject_area <= relative_tolerance * scale * scale ||
          clipper_area <= relative_tolerance * scale * scale)
        return {};

      // Containment first: it is the common case (a small master facet well
      // inside a slave facet or the reverse), and it returns the contained
      // polygon's own vertices rather than recomputed intersections.
      const auto all_inside = [distance](const Polygon<T> &points,
                                         const Polygon<T> &convex) {
        for (const auto &p : points)
          if (!internal::inside_or_on(convex, p, distance))
            return false;
        return true;
      };
      if (all_inside(subject, clipper))
        return subject;
      if (all_inside(clipper, subject))
        return clipper;

      Polygon<T> output = subject;
      Polygon<T> input;
      for (std::size_t e = 0; e < clipper.size() && output.size() >= 3; ++e)
        {
          const Point2D<T> &a = clipper[e];
          const Point2D<T> &b = clipper[(e + 1) % clipper.size()];
          const Point2D<T>  edge{{b[0] - a[0], b[1] - a[1]}};
          // The cross product edge x (p - a) is |edge| times the signed
          // distance of p from the edge's line, positive on the inner
          // (left) side of a counter-clockwise polygon.
          const auto cross = [&a, &edge](const Point2D<T> &p) -> T {
            return edge[0] * (p[1] - a[1]) - edge[1] * (p[0] - a[0]);
          };
          const double on_line =
            distance * std::hypot(value(edge[0]), value(edge[1]));
          // -1 outside, 0 on the line, +1 inside.
          const auto side = [on_line](const T &d) {
            return value(d) > on_line ? 1 : (value(d) < -on_line ? -1 : 0);
          };

          input.swap(output);
          output.clear();
          const std::size_t n = input.size();
          for (std::size_t i = 0; i < n; ++i)
            {
              const Point2D<T> &p      = input[i];
              const Point2D<T> &q      = input[(i + 1) % n];
              const T           d_p    = cross(p);
              const T           d_q    = cross(q);
              const int         side_p = side(d_p);
              const int         side_q = side(d_q);
              if (side_p >= 0)
                output.push_back(p);
              if (side_p * side_q < 0)
                {
                  const T t = d_p / (d_p - d_q);
                  output.push_back(Point2D<T>{
                    {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])}});
                }
            }
          output = merge_coincident_vertices(output, distance);
        }

      if (output.size() < 3 ||
          std::abs(value(signed_area(output))) <=
            relative_tolerance * std::min(subject_area, clipper_area))
        return {};
      return output;
    }

    // ------------------------------------------------------------------
    // Quadrature on convex polygons
    // ------------------------------------------------------------------

    /// A quadrature point: where, and its weight (an area).
    template <typename T>
    struct QuadraturePoint
    {
      /// Position in the plane.
      Point2D<T> point;
      /// Weight: sum over a polygon's points is its area.
      T weight;
    };

    /// A point of the triangle rule in barycentric coordinates with its
    /// weight as a fraction of the triangle's area.
    struct TriangleRulePoint
    {
      /// Barycentric coordinates (they sum to one).
      std::array<double, 3> barycentric;
      /// Weight relative to the triangle's area (the weights sum to one).
      double weight;
    };

    /// The largest degree triangle_rule() provides.
    constexpr unsigned int max_triangle_rule_degree = 13;

    /// A triangle rule exact for polynomials of degree @p degree (odd, at
    /// most max_triangle_rule_degree; an even degree gets the next odd
    /// one): deal.II's Witherden-Vincent rule with (degree + 1) / 2 points
    /// per direction, in barycentric coordinates with weights as fractions
    /// of the area. All points lie inside the triangle and all weights are
    /// positive. Degree 5 is the 7-point rule of Radon (Stroud's T2:5-1);
    /// degrees 7, 9, 11 and 13 have 15, 19, 28 and 37 points. The unit tests
    /// check them monomial by monomial against `int_T x^a y^b = a! b! / (a + b
    /// + 2)!` on the reference triangle.
    inline const std::vector<TriangleRulePoint> &
    triangle_rule(const unsigned int degree = 5)
    {
      static const auto rules = [] {
        std::array<std::vector<TriangleRulePoint>,
                   (max_triangle_rule_degree + 1) / 2>
          r;
        for (unsigned int n = 1; n <= r.size(); ++n)
          {
            const dealii::QWitherdenVincentSimplex<2> q(n);
            for (unsigned int i = 0; i < q.size(); ++i)
              {
                const auto &x = q.point(i);
                // deal.II's reference triangle (0,0), (1,0), (0,1) has
                // area 1/2.
                r[n - 1].push_back(
                  TriangleRulePoint{{{1. - x[0] - x[1], x[0], x[1]}},
                                    2. * q.weight(i)});
              }
          }
        return r;
      }();
      AssertThrow(degree >= 1 && degree <= max_triangle_rule_degree,
                  dealii::ExcMessage("no triangle rule of degree " +
                                     std::to_string(degree)));
      return rules[(degree + 1) / 2 - 1];
    }

    /// Quadrature points on the convex polygon @p polygon (either
    /// orientation): the polygon is split into triangles from its
    /// vertex_mean(), one per edge, and each gets triangle_rule(@p degree).
    /// Exact for polynomials of degree up to @p degree on convex polygons
    /// (each triangle is then non-inverted and the rule is exact on each).
    /// Callers evaluate several integrands (shape functions, gaps) at the
    /// same points. An empty polygon (no overlap) has no points. Triangles
    /// of zero area (from collinear vertices that clipping may leave) give
    /// zero weights.
    template <typename T>
    std::vector<QuadraturePoint<T>>
    quadrature(const Polygon<T> &polygon, const unsigned int degree = 5)
    {
      std::vector<QuadraturePoint<T>> points;
      const std::size_t               n = polygon.size();
      if (n < 3)
        return points;
      // Signed triangle areas times this are positive for either orientation.
      const double orientation = value(signed_area(polygon)) < 0. ? -1. : 1.;
      const Point2D<T> c       = vertex_mean(polygon);
      const auto      &rule    = triangle_rule(degree);
      points.reserve(rule.size() * n);
      for (std::size_t i = 0; i < n; ++i)
        {
          const Point2D<T> &p = polygon[i];
          const Point2D<T> &q = polygon[(i + 1) % n];
          const T           triangle_area =
            0.5 * orientation *
            ((p[0] - c[0]) * (q[1] - c[1]) - (q[0] - c[0]) * (p[1] - c[1]));
          for (const auto &r : rule)
            points.push_back(QuadraturePoint<T>{
              Point2D<T>{{r.barycentric[0] * c[0] + r.barycentric[1] * p[0] +
                            r.barycentric[2] * q[0],
                          r.barycentric[0] * c[1] + r.barycentric[1] * p[1] +
                            r.barycentric[2] * q[1]}},
              r.weight * triangle_area});
        }
      return points;
    }

    namespace internal
    {
      /// Whether @p R is a std::array (integrands with several components).
      template <typename R>
      struct IsStdArray : std::false_type
      {};

      /// A std::array is one.
      template <typename U, std::size_t n>
      struct IsStdArray<std::array<U, n>> : std::true_type
      {};
    } // namespace internal

    /// The integral over the convex polygon @p polygon of @p f, a function
    /// of a Point2D<T> that returns a scalar or a std::array of scalars (so
    /// that several integrands share one evaluation), by
    /// quadrature(@p polygon, @p degree). Exact if @p f is a polynomial of
    /// degree up to @p degree. An empty polygon gives zero.
    template <typename T, typename F>
    auto
    integrate(const Polygon<T>  &polygon,
              const F           &f,
              const unsigned int degree = 5)
    {
      using Result = std::decay_t<decltype(f(std::declval<Point2D<T>>()))>;
      Result sum{};
      if constexpr (internal::IsStdArray<Result>::value)
        for (auto &x : sum)
          x = 0.;
      else
        sum = 0.;
      for (const auto &q : quadrature(polygon, degree))
        {
          const Result value_at_point = f(q.point);
          if constexpr (internal::IsStdArray<Result>::value)
            for (std::size_t i = 0; i < sum.size(); ++i)
              sum[i] += q.weight * value_at_point[i];
          else
            sum += q.weight * value_at_point;
        }
      return sum;
    }

    // ------------------------------------------------------------------
    // Facets: vertex order and inverse maps
    // ------------------------------------------------------------------

    /// glide's quadrilateral facets are deal.II faces with their vertices in
    /// lexicographic order: 0 at (0,0), 1 at (1,0), 2 at (0,1), 3 at (1,1)
    /// of [0,1]^2. Around the facet (counter-clockwise in the parameter
    /// plane) they come in the order 0, 1, 3, 2: polygon vertex `k` is
    /// lexicographic vertex `polygon_order_of_quadrilateral()[k]`.
    inline constexpr std::array<unsigned int, 4>
    polygon_order_of_quadrilateral()
    {
      return {{0, 1, 3, 2}};
    }

    /// The polygon of a quadrilateral facet whose vertices @p lexicographic
    /// come in deal.II's lexicographic order (see
    /// polygon_order_of_quadrilateral()). Counter-clockwise if the facet's
    /// parameter directions form a right-handed frame in the plane.
    template <typename T>
    Polygon<T>
    quadrilateral_polygon(const std::array<Point2D<T>, 4> &lexicographic)
    {
      Polygon<T> polygon;
      for (const unsigned int v : polygon_order_of_quadrilateral())
        polygon.push_back(lexicographic[v]);
      return polygon;
    }

    /// The point of the bilinear quadrilateral with vertices
    /// @p lexicographic (lexicographic order) at parameters @p xi in
    /// [0,1]^2: `x = v0 (1-s)(1-t) + v1 s (1-t) + v2 (1-s) t + v3 s t`.
    template <typename T>
    Point2D<T>
    bilinear_map(const std::array<Point2D<T>, 4> &lexicographic,
                 const Point2D<T>                &xi)
    {
      const T s = xi[0], t = xi[1];
      const T N[4] = {(1. - s) * (1. - t), s * (1. - t), (1. - s) * t, s * t};
      Point2D<T> x{{T(0.), T(0.)}};
      for (unsigned int v = 0; v < 4; ++v)
        for (unsigned int d = 0; d < 2; ++d)
          x[d] += N[v] * lexicographic[v][d];
      return x;
    }

    /// The point of the linear triangle with vertices @p vertices at
    /// parameters @p xi: `x = v0 + xi_0 (v1 - v0) + xi_1 (v2 - v0)`.
    template <typename T>
    Point2D<T>
    triangle_map(const std::array<Point2D<T>, 3> &vertices,
                 const Point2D<T>                &xi)
    {
      Point2D<T> x;
      for (unsigned int d = 0; d < 2; ++d)
        x[d] = vertices[0][d] + xi[0] * (vertices[1][d] - vertices[0][d]) +
               xi[1] * (vertices[2][d] - vertices[0][d]);
      return x;
    }

    /// What an inverse map found.
    enum class InverseMapStatus
    {
      /// The parameters map to the point, and lie in the element (within the
      /// tolerance the caller gave).
      inside,
      /// The parameters map to the point, but lie outside the element by
      /// more than the tolerance: the point is not on this facet.
      outside,
      /// Newton did not converge within max_newton_iterations or ran away
      /// (a folded or badly distorted element, or a point far outside).
      not_converged,
      /// The map's Jacobian is singular (a degenerate element: collinear or
      /// coincident vertices).
      singular
    };

    /// Result of an inverse map: the parameters and what happened. The
    /// parameters are meaningful for `inside` and `outside` only.
    template <typename T>
    struct InverseMap
    {
      /// Parameter coordinates of the point.
      Point2D<T> xi;
      /// Inside, outside, not converged or singular.
      InverseMapStatus status;
      /// Newton iterations taken (0 for the triangle's direct solve).
      unsigned int iterations;
    };

    /// Newton's method for the bilinear inverse map converges quadratically
    /// from the element centre for any reasonably shaped element: a handful
    /// of iterations. Twenty leave a wide margin; needing more means the
    /// iteration is not converging.
    inline constexpr unsigned int max_newton_iterations = 20;

    /// Newton stops when its step in parameter space (coordinates of size 1)
    /// is below this: with quadratic convergence the error after such a
    /// step is at round-off level.
    inline constexpr double newton_step_tolerance = 1e-13;

    /**
     * True if a Newton iteration in parameter coordinates has reached the
     * round-off floor: the step @p step no longer halves from the previous
     * one @p previous_step, and both are below 1e-8 (Newton that still
     * converges shrinks its step quadratically there). The floor is about
     * machine epsilon times the coordinates' size over the facet's size:
     * 1.7e-14 for a master facet of 0.025 at coordinates of 4 in the
     * ironing scene, above a fixed 1e-14; treating that as failure dropped
     * random quadrature points, and Newton on the contact problem stalled
     * on the noise.
     */
    inline bool
    newton_stalled(const double step, const double previous_step)
    {
      return step < 1e-8 && previous_step < 1e-8 && step > 0.5 * previous_step;
    }

    /// Default tolerance (in parameter units) by which a point may lie
    /// outside the element and still count as inside: above the round-off
    /// of the map, below anything geometrically meaningful.
    inline constexpr double default_outside_tolerance = 1e-10;

    namespace internal
    {
      /// One Newton correction `xi - J^{-1} (x(xi) - x)` of the bilinear
      /// inverse map, in the scalar type of its arguments. Returns false if
      /// J is singular relative to the element's size @p scale.
      template <typename T>
      bool
      bilinear_newton_step(const std::array<Point2D<T>, 4> &v,
                           const Point2D<T>                &x,
                           const double                     scale,
                           Point2D<T>                      &xi)
      {
        const Point2D<T> r0 = bilinear_map(v, xi);
        const Point2D<T> r{{r0[0] - x[0], r0[1] - x[1]}};
        const T          s = xi[0], t = xi[1];
        // Columns dx/ds and dx/dt.
        T J[2][2];
        for (unsigned int d = 0; d < 2; ++d)
          {
            J[d][0] = (1. - t) * (v[1][d] - v[0][d]) + t * (v[3][d] - v[2][d]);
            J[d][1] = (1. - s) * (v[2][d] - v[0][d]) + s * (v[3][d] - v[1][d]);
          }
        const T det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (std::abs(value(det)) <= relative_tolerance * scale * scale)
          return false;
        const T ds = (J[1][1] * r[0] - J[0][1] * r[1]) / det;
        const T dt = (J[0][0] * r[1] - J[1][0] * r[0]) / det;
        xi[0] -= ds;
        xi[1] -= dt;
        return true;
      }
    } // namespace internal

    /// Parameters in [0,1]^2 of the point @p x of the plane on the bilinear
    /// quadrilateral with vertices @p lexicographic (deal.II's lexicographic
    /// order). Newton's method from the centre (0.5, 0.5), on the values;
    /// once converged, one more Newton step in @p T, which (the residual
    /// being zero to round-off) gives the exact first derivatives of the
    /// parameters with respect to the vertices and @p x by the implicit
    /// function theorem. The status says whether the point is inside (up to
    /// @p outside_tolerance in parameter units), outside, or whether Newton
    /// failed (not converged, ran away beyond 100 element sizes, or met a
    /// singular Jacobian).
    template <typename T>
    InverseMap<T>
    inverse_bilinear_map(
      const std::array<Point2D<T>, 4> &lexicographic,
      const Point2D<T>                &x,
      const double outside_tolerance = default_outside_tolerance)
    {
      std::array<Point2D<double>, 4> v;
      for (unsigned int i = 0; i < 4; ++i)
        v[i] = value(lexicographic[i]);
      const Point2D<double> x_value = value(x);
      double                scale   = 0.;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int j = i + 1; j < 4; ++j)
          scale =
            std::max(scale, std::hypot(v[i][0] - v[j][0], v[i][1] - v[j][1]));

      InverseMap<T>   result{{{T(0.5), T(0.5)}},
                           InverseMapStatus::not_converged,
                           0};
      Point2D<double> xi{{0.5, 0.5}};
      bool            converged     = false;
      double          previous_step = std::numeric_limits<double>::max();
      while (result.iterations < max_newton_iterations)
        {
          ++result.iterations;
          const Point2D<double> previous = xi;
          if (!internal::bilinear_newton_step(v, x_value, scale, xi))
            {
              result.status = InverseMapStatus::singular;
              return result;
            }
          // Far outside the element: not a point of this facet, and the
          // bilinear map extrapolated that far may fold.
          if (std::abs(xi[0]) > 100. || std::abs(xi[1]) > 100.)
            return result;
          // Converged, or at the round-off floor of the map (a small facet
          // far from the origin: the step stalls below 1e-8 instead of
          // shrinking quadratically; see newton_stalled()).
          const double step = std::max(std::abs(xi[0] - previous[0]),
                                       std::abs(xi[1] - previous[1]));
          if (step <= newton_step_tolerance ||
              newton_stalled(step, previous_step))
            {
              converged = true;
              break;
            }
          previous_step = step;
        }
      if (!converged)
        return result;

      result.xi = {{T(xi[0]), T(xi[1])}};
      if (!internal::bilinear_newton_step(lexicographic, x, scale, result.xi))
        {
          result.status = InverseMapStatus::singular;
          return result;
        }
      const double s = value(result.xi[0]), t = value(result.xi[1]);
      result.status = (s >= -outside_tolerance && s <= 1. + outside_tolerance &&
                       t >= -outside_tolerance && t <= 1. + outside_tolerance) ?
                        InverseMapStatus::inside :
                        InverseMapStatus::outside;
      return result;
    }

    /// Parameters of the point @p x of the plane on the linear triangle
    /// with vertices @p vertices (see triangle_map(); the element is
    /// `xi_0, xi_1 >= 0, xi_0 + xi_1 <= 1`): a 2x2 linear solve in @p T, so
    /// the derivatives are exact. Singular for a degenerate triangle.
    template <typename T>
    InverseMap<T>
    inverse_triangle_map(
      const std::array<Point2D<T>, 3> &vertices,
      const Point2D<T>                &x,
      const double outside_tolerance = default_outside_tolerance)
    {
      InverseMap<T>    result{{{T(0.), T(0.)}}, InverseMapStatus::singular, 0};
      const T          a   = vertices[1][0] - vertices[0][0];
      const T          b   = vertices[2][0] - vertices[0][0];
      const T          c   = vertices[1][1] - vertices[0][1];
      const T          d   = vertices[2][1] - vertices[0][1];
      const T          det = a * d - b * c;
      const Polygon<T> triangle(vertices.begin(), vertices.end());
      const double     scale = size(triangle);
      if (std::abs(value(det)) <= relative_tolerance * scale * scale)
        return result;
      const T rx     = x[0] - vertices[0][0];
      const T ry     = x[1] - vertices[0][1];
      result.xi[0]   = (d * rx - b * ry) / det;
      result.xi[1]   = (a * ry - c * rx) / det;
      const double s = value(result.xi[0]), t = value(result.xi[1]);
      result.status = (s >= -outside_tolerance && t >= -outside_tolerance &&
                       s + t <= 1. + outside_tolerance) ?
                        InverseMapStatus::inside :
                        InverseMapStatus::outside;
      return result;
    }

    /// Inverse of a small square matrix @p A in place (Gauss-Jordan with
    /// pivoting on the values; the dual basis A = D M^{-1} of a facet);
    /// false if singular.
    template <typename T>
    bool
    invert_small(std::vector<std::vector<T>> &A)
    {
      const unsigned int          n = A.size();
      std::vector<std::vector<T>> B(n, std::vector<T>(n, T(0.)));
      for (unsigned int i = 0; i < n; ++i)
        B[i][i] = 1.;
      for (unsigned int c = 0; c < n; ++c)
        {
          unsigned int r = c;
          for (unsigned int i = c + 1; i < n; ++i)
            if (std::abs(value(A[i][c])) > std::abs(value(A[r][c])))
              r = i;
          if (!(std::abs(value(A[r][c])) > 0.))
            return false;
          std::swap(A[r], A[c]);
          std::swap(B[r], B[c]);
          const T pivot = A[c][c];
          for (unsigned int j = 0; j < n; ++j)
            {
              A[c][j] /= pivot;
              B[c][j] /= pivot;
            }
          for (unsigned int i = 0; i < n; ++i)
            if (i != c)
              {
                const T factor = A[i][c];
                for (unsigned int j = 0; j < n; ++j)
                  {
                    A[i][j] -= factor * A[c][j];
                    B[i][j] -= factor * B[c][j];
                  }
              }
        }
      A = B;
      return true;
    }

  } // namespace mortar_geometry
} // namespace glide
