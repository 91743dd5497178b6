// Unit tests of small sliding (issue 4: R6.3, R7.1-R7.3, R8.1, R8.2,
// R10.1, R11.1-R11.3). Why the expected answers are right: on a circle
// faceted with equal facets the averaged nodal normals are radial, and the
// normal field interpolated from them along a chord is parallel to the
// chord point's radius, so every normal line passes through the center and
// the anchor of a point is where its ray from the center crosses the
// facets; at the end of a master on a symmetry plane the adjusted normal
// lies in the plane; a user normal replaces the average; on a straight
// facet the load-transfer weights are the linear shape functions at the
// slave node's foot point, clamped to the facet; a rigid rotation of
// everything turns the plane with the facet and leaves gap and weights
// alone; in infinitesimal sliding nothing the master does changes the
// normal or the weights; and the contact Jacobian must be the derivative
// of the contact residual (central finite differences).
#include <glide/contact/contact.h>
#include <glide/contact/small_sliding.h>

#include "test_helpers.h"
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace dealii;
using namespace glide;

namespace
{
  /// A ball (hertz mesh) dipping into a block [0,1]^dim (0.05, in 3D
  /// 0.15), as in the master surface tests, with small sliding; the ball's
  /// curved surface is the master, the block's top the slave.
  std::string
  ball_on_block(const unsigned int dim,
                const unsigned int degree,
                const bool         nonlinear,
                const std::string &enforcement,
                const std::string &ball_top = "fixed",
                const std::string &extra    = "")
  {
    const bool         three = dim == 3;
    std::ostringstream s;
    s << "set Dimension = " << dim
      << "\nset Analysis type = " << (three ? "3d" : "plane strain")
      << "\nsubsection Discretization\n  set Element degree = " << degree
      << "\n  set Geometric nonlinearity = " << (nonlinear ? "true" : "false")
      << "\nend\nset Bodies = block, ball"
      << "\nset Boundary conditions = hold, top"
      << "\nset Contact pairs = pair\n"
      << "subsection Body block\n  subsection Block\n    set Lower corner = "
      << (three ? "0, 0, 0" : "0, 0")
      << "\n    set Upper corner = " << (three ? "1, 1, 1" : "1, 1")
      << "\n    set Subdivisions = " << (three ? "4, 2, 4" : "5, 2")
      << "\n  end\nend\n"
      << "subsection Body ball\n  set Mesh = hertz\n  subsection Round shapes\n"
      << "    set Center = " << (three ? "0.05, 1.85, 0.05" : "0.5, 1.95")
      << "\n    set Radius = 1\n  end\n"
      << "  subsection Refinement\n    set Global refinements = 1"
      << "\n  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = block.bottom\n"
      << "  set Type = fixed\nend\n"
      << "subsection Boundary condition top\n  set Surface = ball.flat\n"
      << "  set Type = " << ball_top << "\nend\n"
      << "subsection Contact pair pair\n  set Slave = block.top\n"
      << "  set Master = ball.curved\n  set Sliding = small\n"
      << "  set Enforcement = " << enforcement << "\n"
      << extra << "end\n";
    return s.str();
  }

  /// A disk of radius 1 around the origin (Mesh = cylinder: equal facets
  /// on its circle) and a block below it.
  std::string
  disk(const unsigned int refinements)
  {
    std::ostringstream s;
    s << "set Dimension = 2\nset Bodies = block, disk\n"
      << "set Boundary conditions = hold\nset Contact pairs = pair\n"
      << "subsection Body block\n  subsection Block\n"
      << "    set Lower corner = -1, -2\n    set Upper corner = 1, -1.01\n"
      << "  end\nend\n"
      << "subsection Body disk\n  set Mesh = cylinder\n"
      << "  subsection Round shapes\n    set Center = 0, 0\n"
      << "    set Radius = 1\n  end\n"
      << "  subsection Refinement\n    set Global refinements = " << refinements
      << "\n  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = block.bottom\n"
      << "  set Type = fixed\nend\n"
      << "subsection Contact pair pair\n  set Slave = block.top\n"
      << "  set Master = disk.outer\n  set Sliding = small\nend\n";
    return s.str();
  }

  template <int dim>
  void
  check_jacobian(const unsigned int degree,
                 const bool         nonlinear,
                 const std::string &enforcement,
                 const bool         sts = false)
  {
    const std::string tag = std::to_string(dim) + "D Q" +
                            std::to_string(degree) +
                            (nonlinear ? " small" : " infinitesimal") + " " +
                            enforcement + (sts ? " STS" : " NTS");
    glide_test::ContactFixture<dim> s(
      ball_on_block(dim,
                    degree,
                    nonlinear,
                    enforcement,
                    "fixed",
                    sts ? "  set Formulation = surface to surface\n" : ""),
      "small_" + std::to_string(dim) + std::to_string(degree) +
        (nonlinear ? "n" : "l") + enforcement + (sts ? "sts" : "") + ".prm");
    if (sts)
      {
        unsigned int averaged = 0;
        for (const auto &a : s.contact.anchors(0))
          averaged += a.sts ? 1 : 0;
        // In 3D most block-top regions reach beyond the octant and fall
        // back to node to surface.
        EXPECT_GE(averaged, dim == 2 ? 4u : 1u)
          << tag << ": surface-to-surface constraints";
      }
    // In 3D the ball is an octant x, z >= 0.05: block-top nodes at x = 0 or
    // z = 0 lie beside it.
    unsigned int anchored = 0;
    for (const auto &a : s.contact.anchors(0))
      anchored += a.found ? 1 : 0;
    if (dim == 2)
      EXPECT_EQ(anchored, s.contact.anchors(0).size()) << tag;
    else
      EXPECT_GE(anchored, 12u) << tag;
    glide_test::expect_consistent_jacobian(s, tag, 7);
  }
} // namespace

// R5.1 for small sliding: the Jacobian is the derivative of the residual,
// with the plane turning with its facet and the weights following the
// slave node (small sliding), and for the linear constraint of
// infinitesimal sliding; 2D and 3D, degree 1 and 2, hard and penalty.
TEST(SmallSliding, JacobianMatchesFiniteDifferences)
{
  for (const unsigned int degree : {1u, 2u})
    for (const bool nonlinear : {true, false})
      {
        check_jacobian<2>(degree, nonlinear, "hard");
        check_jacobian<3>(degree, nonlinear, "hard");
      }
  check_jacobian<2>(1, true, "penalty");
  check_jacobian<3>(1, true, "penalty");
}

// R9.1, R9.2: the same for surface to surface (averaging regions with
// several slave nodes per constraint, master weights of the landing zone,
// the plane turning with the anchor facet in nonlinear scenes).
TEST(SmallSliding, SurfaceToSurfaceJacobianMatchesFiniteDifferences)
{
  for (const unsigned int degree : {1u, 2u})
    for (const bool nonlinear : {true, false})
      {
        check_jacobian<2>(degree, nonlinear, "hard", true);
        check_jacobian<3>(degree, nonlinear, "hard", true);
      }
  check_jacobian<2>(2, true, "penalty", true);
}

// R9.1-R9.4 on a flat master (the block's top, facets 0.2 long): a region
// of three slave points 0.1 above it, projected along the slave normal
// (0, -1), lands straight below; the anchor is the participation-weighted
// centre of the landing points, the contact direction (0, 1), the master
// weights those of the landing points (summing to 1, centred on the
// anchor). A tilted slave normal with the slave node on an XSYMM plane
// gives a direction in that plane. A slave normal along the master's own
// normal falls back (same direction), and so does a region that projects
// past the master's end (missed).
TEST(SmallSliding, SurfaceToSurfaceAnchors)
{
  glide_test::ContactFixture<2> s(ball_on_block(2, 1, false, "hard"),
                                  "small_sts_anchor.prm");
  const auto            top = glide_test::master_of<2>(s, "block.top", 0.);
  const SmallSliding<2> planes(*top, {}, true, false);
  using Fallback = SmallSliding<2>::Fallback;
  const std::vector<Point<2>> X{Point<2>(0.3, 1.1),
                                Point<2>(0.25, 1.1),
                                Point<2>(0.35, 1.1)};
  const std::vector<double>   phi{2. / 3., 1. / 6., 1. / 6.};
  Tensor<1, 2>                down;
  down[1] = -1.;
  Fallback   reason;
  const auto a = planes.anchor_sts(X, phi, down, {{false, false}}, reason);
  ASSERT_TRUE(a.found);
  EXPECT_EQ(reason, Fallback::none);
  EXPECT_TRUE(a.sts);
  EXPECT_NEAR(a.X0[0], 0.3, 1e-12);
  EXPECT_NEAR(a.X0[1], 1., 1e-12);
  EXPECT_NEAR(a.N0[0], 0., 1e-12);
  EXPECT_NEAR(a.N0[1], 1., 1e-12);
  double sum = 0., moment = 0.;
  for (unsigned int m = 0; m < a.list.size(); ++m)
    {
      sum += a.weights[m];
      moment += a.weights[m] * top->get_nodes()[a.list[m]].X[0];
    }
  EXPECT_NEAR(sum, 1., 1e-12);
  EXPECT_NEAR(moment, 0.3, 1e-12) << "the weights' centre is the anchor";

  Tensor<1, 2> tilted;
  tilted[0] = 0.3;
  tilted[1] = -1.;
  const auto b =
    planes.anchor_sts(X, phi, tilted / tilted.norm(), {{true, false}}, reason);
  ASSERT_TRUE(b.found);
  EXPECT_NEAR(b.N0[0], 0., 1e-12) << "R9.3: in the symmetry plane";
  EXPECT_NEAR(b.N0[1], 1., 1e-12);
  // Slave normal (0, 1): along the master's outward normal.
  const auto c = planes.anchor_sts(X, phi, -down, {{false, false}}, reason);
  EXPECT_FALSE(c.found);
  EXPECT_EQ(reason, Fallback::same_direction);
  const std::vector<Point<2>> off{Point<2>(0.98, 1.1),
                                  Point<2>(0.93, 1.1),
                                  Point<2>(1.03, 1.1)};
  const auto d = planes.anchor_sts(off, phi, down, {{false, false}}, reason);
  EXPECT_FALSE(d.found);
  EXPECT_EQ(reason, Fallback::missed);
}

// R7.1-R7.3: anchors on a circle of equal facets lie on the ray from the
// center through the slave point, and the plane normal N0 is along it.
TEST(SmallSliding, AnchorsOnAFacetedCircleLieOnTheRayFromItsCenter)
{
  glide_test::ContactFixture<2> s(disk(2), "small_disk.prm");
  const auto            master = glide_test::master_of<2>(s, "disk.outer", 0.);
  const SmallSliding<2> planes(*master, {}, true, false);
  for (const auto &n : planes.nodal_normals())
    EXPECT_NEAR(n.norm(), 1., 1e-12);
  for (unsigned int k = 0; k < master->get_nodes().size(); ++k)
    {
      const Point<2> &X = master->get_nodes()[k].X;
      EXPECT_NEAR((planes.nodal_normals()[k] - X / X.norm()).norm(), 0., 1e-12)
        << "the averaged normal of a node of equal facets is radial";
    }
  const unsigned int n_facets = master->get_facets().size();
  for (const double angle : {-2.0, -1.3, -0.7, 0.1, 0.77, 2.9})
    for (const double radius : {0.97, 1.0, 1.08})
      {
        const Point<2> X(radius * std::cos(angle), radius * std::sin(angle));
        const auto     a = planes.anchor(X);
        ASSERT_TRUE(a.found) << "angle " << angle;
        // On the ray through X ...
        EXPECT_NEAR(a.X0[0] * X[1] - a.X0[1] * X[0], 0., 1e-12);
        EXPECT_GT(a.X0 * X, 0.);
        // ... on the chord of the facet that holds it ...
        const double half = numbers::PI / n_facets;
        EXPECT_NEAR(a.X0.norm() *
                      std::cos(std::fmod(angle + 4 * numbers::PI, 2 * half) -
                               half),
                    std::cos(half),
                    1e-12)
          << "angle " << angle;
        // ... with the plane normal along the ray.
        EXPECT_NEAR((a.N0 - X / X.norm()).norm(), 0., 1e-12);
        // The load list: the facet's two nodes, or three at a node.
        EXPECT_EQ(a.list.size(), a.node >= 0 ? 3u : 2u);
      }
}

// R8.1, R8.2: the ends of the ball's curved surface lie on the plane of its
// flat top. Plain averages tilt their normals by half a facet angle; with
// YSYMM on the flat top they lie in the plane; a user normal replaces
// either.
TEST(SmallSliding, SymmetryPlanesAndUserNormalsAtTheMastersEnds)
{
  for (const std::string bc : {"fixed", "YSYMM"})
    {
      glide_test::ContactFixture<2> s(ball_on_block(2, 1, false, "hard", bc),
                                      "small_ends_" + bc + ".prm");
      const auto master = glide_test::master_of<2>(s, "ball.curved", 0.);
      const SmallSliding<2> planes(*master, {}, true, false);
      unsigned int          ends = 0;
      for (unsigned int k = 0; k < master->get_nodes().size(); ++k)
        {
          const Point<2> &X = master->get_nodes()[k].X;
          if (std::abs(X[1] - 1.95) > 1e-9)
            continue;
          ++ends;
          const double side = X[0] > 0.5 ? 1. : -1.;
          const auto  &n    = planes.nodal_normals()[k];
          if (bc == "YSYMM")
            {
              EXPECT_NEAR(n[0], side, 1e-12);
              EXPECT_NEAR(n[1], 0., 1e-12);
            }
          else
            EXPECT_LT(n[1], -0.05) << "tilted towards the facet";

          std::map<unsigned int, Tensor<1, 2>> user;
          user[k][0] = 3.;
          user[k][1] = 4.;
          const SmallSliding<2> custom(*master, user, true, false);
          EXPECT_NEAR(custom.nodal_normals()[k][0], 0.6, 1e-15);
          EXPECT_NEAR(custom.nodal_normals()[k][1], 0.8, 1e-15);
        }
      EXPECT_EQ(ends, 2u);
    }
}

// R11.1-R11.3: on the flat top of the block (a master here), the weights
// of a slave node are the linear shape functions of the anchor facet at
// its foot point, clamped to the facet when it slides off; the list never
// changes; an anchor at a node lists that node and its neighbours and
// loads the facet under the slave node.
TEST(SmallSliding, LoadTransferWeights)
{
  glide_test::ContactFixture<2> s(ball_on_block(2, 1, false, "hard"),
                                  "small_weights.prm");
  const auto            top = glide_test::master_of<2>(s, "block.top", 0.);
  const SmallSliding<2> planes(*top, {}, false, false);
  // Facets of length 0.2 on y = 1.
  const auto a = planes.anchor(Point<2>(0.25, 1.1));
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.node, -1);
  ASSERT_EQ(a.list.size(), 2u);
  EXPECT_NEAR(a.X0[0], 0.25, 1e-12);
  EXPECT_NEAR(a.X0[1], 1., 1e-12);
  const auto x_of = [&](const unsigned int k) {
    return top->get_nodes()[a.list[k]].X[0];
  };
  for (const double x : {0.21, 0.25, 0.39, 0.5, 0.9})
    {
      const auto   w = planes.weights(a, Point<2>(x, 1.05));
      const double s = std::clamp((x - 0.2) / 0.2, 0., 1.);
      ASSERT_EQ(w.size(), 2u) << "the list never grows";
      for (unsigned int k = 0; k < 2; ++k)
        EXPECT_NEAR(w[k], std::abs(x_of(k) - 0.2) < 1e-12 ? 1 - s : s, 1e-12)
          << "x = " << x;
      const auto plane = planes.plane(a, Point<2>(x, 1.05));
      EXPECT_NEAR(plane.gap, 0.05, 1e-12);
    }
  // At the node x = 0.4: three nodes; a slave node left of it loads the
  // left facet, one right of it the right facet.
  const auto b = planes.anchor(Point<2>(0.4, 0.98));
  ASSERT_TRUE(b.found);
  ASSERT_GE(b.node, 0);
  ASSERT_EQ(b.list.size(), 3u);
  for (const double x : {0.33, 0.45})
    {
      const auto w   = planes.weights(b, Point<2>(x, 0.98));
      double     sum = 0.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          const double X        = top->get_nodes()[b.list[k]].X[0];
          const double expected = std::max(0., 1. - std::abs(X - x) / 0.2);
          EXPECT_NEAR(w[k], expected, 1e-12) << "x = " << x << ", node " << X;
          sum += w[k];
        }
      EXPECT_NEAR(sum, 1., 1e-12);
    }
}

// R10.1: small sliding in a geometrically nonlinear scene. Turning master
// and slave point rigidly by 90 degrees turns the plane normal with the
// facet and changes neither gap nor weights. R6.3: in infinitesimal
// sliding the same motion changes neither the normal nor the weights.
TEST(SmallSliding, PlanesTurnWithTheFacetUnlessSlidingIsInfinitesimal)
{
  glide_test::ContactFixture<2> s(ball_on_block(2, 2, true, "hard"),
                                  "small_turn.prm");
  auto           master = glide_test::master_of<2>(s, "ball.curved", 0.2);
  const Point<2> X(0.62, 1.0);
  const auto rotate = [](const Point<2> &p) { return Point<2>(-p[1], p[0]); };
  VectorType U(s.e.locally_owned(), MPI_COMM_WORLD);
  for (const auto &node : master->get_nodes())
    {
      const Point<2> y = rotate(node.X);
      for (unsigned int d = 0; d < 2; ++d)
        U[node.dofs[d]] = y[d] - node.X[d];
    }
  for (const bool infinitesimal : {false, true})
    {
      master->set_displacement(VectorType());
      const SmallSliding<2> planes(*master, {}, infinitesimal, false);
      const auto            a = planes.anchor(X);
      ASSERT_TRUE(a.found);
      const auto before = planes.plane(a, X);
      const auto w0     = planes.weights(a, X);
      master->set_displacement(U);
      const auto after  = planes.plane(a, rotate(X));
      const auto w1     = planes.weights(a, rotate(X));
      const auto turned = rotate(Point<2>(before.normal));
      if (!infinitesimal)
        {
          EXPECT_NEAR(after.gap, before.gap, 1e-12);
          EXPECT_NEAR((Point<2>(after.normal) - turned).norm(), 0., 1e-12);
          EXPECT_NEAR((after.point - rotate(before.point)).norm(), 0., 1e-12);
        }
      else
        EXPECT_NEAR((after.normal - before.normal).norm(), 0., 1e-15)
          << "infinitesimal sliding never turns the plane";
      ASSERT_EQ(w0.size(), w1.size());
      for (unsigned int k = 0; k < w0.size(); ++k)
        EXPECT_NEAR(w0[k], w1[k], infinitesimal ? 0. : 1e-12);
      for (unsigned int k = 0; k < w0.size(); ++k)
        EXPECT_DOUBLE_EQ(w0[k], a.weights[k]) << "initial weights";
    }
}

// R10.1, R13.1 in 3D: a rigid rotation by 90 degrees about (1, 1, 1) of
// master and slave point turns the plane normal and both local tangents
// with it (the tangents are not re-derived from the global x axis) and
// keeps the gap.
TEST(SmallSliding, TangentsTurnWithTheFacetIn3D)
{
  glide_test::ContactFixture<3> s(ball_on_block(3, 1, true, "hard"),
                                  "small_turn_3d.prm");
  auto         master = glide_test::master_of<3>(s, "ball.curved", 0.2);
  Tensor<1, 3> axis;
  axis[0] = axis[1] = axis[2] = 1. / std::sqrt(3.);
  // Rodrigues for 90 degrees: R v = (a.v) a + a x v.
  const auto rotate = [&](const Tensor<1, 3> &v) {
    return Tensor<1, 3>((axis * v) * axis + cross_product_3d(axis, v));
  };
  const Point<3> X(0.3, 1.0, 0.3);
  VectorType     U(s.e.locally_owned(), MPI_COMM_WORLD);
  for (const auto &node : master->get_nodes())
    {
      const Tensor<1, 3> y = rotate(node.X);
      for (unsigned int d = 0; d < 3; ++d)
        U[node.dofs[d]] = y[d] - node.X[d];
    }
  master->set_displacement(VectorType());
  const SmallSliding<3> planes(*master, {}, false, false);
  const auto            a = planes.anchor(X);
  ASSERT_TRUE(a.found);
  const auto before = planes.plane(a, X);
  master->set_displacement(U);
  const auto after = planes.plane(a, Point<3>(rotate(X)));
  EXPECT_NEAR(after.gap, before.gap, 1e-12);
  EXPECT_NEAR((after.normal - rotate(before.normal)).norm(), 0., 1e-12);
  for (unsigned int t = 0; t < 2; ++t)
    {
      EXPECT_NEAR((after.tangents[t] - rotate(before.tangents[t])).norm(),
                  0.,
                  1e-12)
        << "tangent " << t + 1;
      EXPECT_NEAR(before.tangents[t] * before.normal, 0., 1e-12);
      EXPECT_NEAR(before.tangents[t].norm(), 1., 1e-12);
    }
  // The convention of R13.1 at the current normal would differ: the turned
  // t1 is not the global x axis projected onto the turned plane.
  const auto convention = contact_tangents<3>(after.normal);
  EXPECT_GT((convention[0] - after.tangents[0]).norm(), 1e-3);
}
