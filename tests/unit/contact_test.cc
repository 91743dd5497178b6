// Unit tests of the contact part (issue 3, R5.1, P1.4, P2.3). Why the
// expected answers are right: analytical rigid masters have closed-form
// gaps and normals (distance to a line, a circle, a sphere); a rigid motion
// moves them as it says; the contact Jacobian must be the derivative of the
// contact residual, checked against central finite differences for hard
// and penalty enforcement on flat and curved masters, in 2D and 3D, in
// states with open and closed nodes.
#include <glide/contact/active_set_monitor.h>
#include <glide/contact/contact.h>
#include <glide/mechanics/elasticity.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/timer.h>

#include "test_helpers.h"
#include <gtest/gtest.h>

#include <random>
#include <sstream>

using namespace dealii;
using namespace glide;

namespace
{
  ContactPairParameters
  rigid(const MasterType type, const bool inside = false)
  {
    ContactPairParameters p;
    p.master_type  = type;
    p.point        = {1., 2., 0.};
    p.normal       = {0., 2., 0.};
    p.radius       = 0.5;
    p.slave_inside = inside;
    return p;
  }
} // namespace

TEST(RigidMaster, PlaneGapAndNormal)
{
  RigidMaster<2> m(rigid(MasterType::rigid_plane), "pair");
  const auto     p = m.project(Point<2>(3., 2.5));
  EXPECT_NEAR(p.gap, 0.5, 1e-14);
  EXPECT_NEAR(p.normal[1], 1., 1e-14);
  EXPECT_NEAR(p.closest_point[1], 2., 1e-14);
  EXPECT_NEAR(p.curvature.norm(), 0., 1e-14);
}

TEST(RigidMaster, CircleOutsideAndInside)
{
  RigidMaster<2> out(rigid(MasterType::rigid_circle), "pair");
  const auto     p = out.project(Point<2>(1., 3.));
  EXPECT_NEAR(p.gap, 0.5, 1e-14);
  EXPECT_NEAR(p.normal[1], 1., 1e-14);
  // d2g/dx2 = (I - n n) / r: only the tangential direction.
  EXPECT_NEAR(p.curvature[0][0], 1., 1e-14);
  EXPECT_NEAR(p.curvature[1][1], 0., 1e-14);
  RigidMaster<2> in(rigid(MasterType::rigid_circle, true), "pair");
  const auto     q = in.project(Point<2>(1.3, 2.));
  EXPECT_NEAR(q.gap, 0.2, 1e-14);
  EXPECT_NEAR(q.normal[0], -1., 1e-14);
}

TEST(RigidMaster, CylinderIgnoresTheAxialDirection)
{
  RigidMaster<3> m(rigid(MasterType::rigid_circle), "pair");
  const auto     p = m.project(Point<3>(1., 3., 7.));
  EXPECT_NEAR(p.gap, 0.5, 1e-14);
  EXPECT_NEAR(p.normal[2], 0., 1e-14);
  EXPECT_NEAR(p.curvature[2][2], 0., 1e-14);
  RigidMaster<3> s(rigid(MasterType::rigid_sphere), "pair");
  EXPECT_NEAR(s.project(Point<3>(1., 2., 3.)).gap, 2.5, 1e-14);
}

TEST(RigidMaster, PrescribedMotion)
{
  auto p            = rigid(MasterType::rigid_plane);
  p.translation     = "0; -t";
  p.rotation        = "pi/2*t";
  p.rotation_center = {1., 2., 0.};
  RigidMaster<2> m(p, "pair");
  m.set_time(1.);
  // The plane through (1, 2) with normal (0, 1), rotated by 90 degrees about
  // (1, 2) and moved down by 1: through (1, 1) with normal (-1, 0).
  const auto q = m.project(Point<2>(0., 5.));
  EXPECT_NEAR(q.normal[0], -1., 1e-12);
  EXPECT_NEAR(q.gap, 1., 1e-12);
}

// R16.3: how deep a slave point's path relative to the master runs
// through it within an increment (Contact::passed_through()). A circle of
// radius 0.5 at (1, 2) moving by (0, -3) while the point stays at (1.2, 0):
// relative to the master the point goes from 2 below the centre to 1
// above it, 0.2 beside the centre line: depth 0.5 - 0.2. The same for a
// cylinder (the axial coordinate ignored) and a sphere, and the depth for
// a master that turns and moves, for a point in contact at the start. Zero
// for a path that stays outside, a point in contact (within the clearance)
// at its end, a path no deeper than its start, a plane, and a slave inside
// a hole.
TEST(RigidMaster, PassageDepth)
{
  auto p        = rigid(MasterType::rigid_circle);
  p.translation = "0; -3*t";
  RigidMaster<2> circle(p, "pair");
  EXPECT_NEAR(
    circle.passage_depth(Point<2>(1.2, 0.), 0., Point<2>(1.2, 0.), 1., 0.),
    0.3,
    1e-12);
  // Beside it by more than the radius: never inside.
  EXPECT_EQ(
    circle.passage_depth(Point<2>(1.6, 0.), 0., Point<2>(1.6, 0.), 1., 0.), 0.);
  // Half way only (t = 0.5: centre at (1, 0.5)): the point at (1.2, 0)
  // ends 0.54 from the centre, outside; its path stays outside.
  EXPECT_EQ(
    circle.passage_depth(Point<2>(1.2, 0.), 0., Point<2>(1.2, 0.), 0.5, 0.),
    0.);
  // Within the clearance of the master's surface at the end (in contact)
  // on the side it started: not a passage (an eighth of a turn round the
  // circle, its chord 0.038 deep; it could slide round)...
  EXPECT_EQ(circle.passage_depth(Point<2>(1., 1.5),
                                 0.,
                                 Point<2>(1. + 0.5 * std::sqrt(0.5),
                                          2. - 0.5 * std::sqrt(0.5) - 3e-6),
                                 1e-6,
                                 1e-9),
            0.);
  // ... nor on the far side after sliding round in contact by 100 degrees
  // (its chord 0.32 from the centre, outside the inner half; the circle
  // moves by 1e-6 only) ...
  {
    const double turn = 100. * numbers::PI / 180.;
    EXPECT_EQ(circle.passage_depth(Point<2>(1., 1.5),
                                   0.,
                                   Point<2>(1. + 0.5 * std::sin(turn),
                                            2. - 3e-6 - 0.5 * std::cos(turn)),
                                   1e-6,
                                   1e-9),
              0.);
  }
  // ... but on the master's far side from where it started, pushed out
  // through it: the path runs through the centre (until 2026-12-07 not
  // counted, and a circle moved from above a node to below its top in one
  // increment lifted the block with exit 0).
  EXPECT_NEAR(circle.passage_depth(
                Point<2>(1., 0.), 0., Point<2>(1., -0.5 + 1e-12), 1., 1e-9),
              0.5,
              1e-9);
  EXPECT_NEAR(circle.passage_depth(
                Point<2>(1., 0.), 0., Point<2>(1., -0.5 + 1e-12), 1., 0.),
              0.5,
              1e-9);
  // In contact at the start (on the surface, (1, 1.5) below the centre
  // (1, 2)) and passed through: the master's centre runs over it, so the
  // path goes 0.5 deep (until 2026-12-06 only points open at both ends
  // counted, and a circle driven through a block it pressed went
  // unnoticed).
  EXPECT_NEAR(
    circle.passage_depth(Point<2>(1., 1.5), 0., Point<2>(1., 1.5), 1., 1e-9),
    0.5,
    1e-12);
  // 0.1 inside at the start (a penalty's penetration) and left by the
  // master: the path goes no deeper than where it started.
  EXPECT_EQ(
    circle.passage_depth(Point<2>(1., 1.6), 0., Point<2>(1., -2.), 1., 1e-9),
    0.);
  // A half turn about (1, 1), 1 below the centre (1, 2): the centre
  // moves along a half circle through (0, 1) (at t = 0.5, turning
  // counterclockwise) to (1, 0). The point fixed at (0, 1), outside at
  // both ends (sqrt(2) from the centre), is passed by the whole radius;
  // with the turn reversed the centre runs through (2, 1) and never comes
  // nearer than sqrt(2).
  auto q            = rigid(MasterType::rigid_circle);
  q.rotation        = "pi*t";
  q.rotation_center = {1., 1., 0.};
  RigidMaster<2> turning(q, "pair");
  EXPECT_NEAR(
    turning.passage_depth(Point<2>(0., 1.), 0., Point<2>(0., 1.), 1., 0.),
    0.5,
    1e-12);
  q.rotation = "-pi*t";
  RigidMaster<2> reversed(q, "pair");
  EXPECT_EQ(
    reversed.passage_depth(Point<2>(0., 1.), 0., Point<2>(0., 1.), 1., 0.), 0.);
  // A circle that spins about its own centre by a quarter turn and moves
  // by (0.2, 0) under a point on its surface: the point stays on or
  // outside it (0.55 and 0.585 from the centre at the ends), so there is
  // no passage (a chord between the ends in the circle's frame passed
  // 0.3025 / sqrt(0.425) = 0.464 from the centre).
  auto r            = rigid(MasterType::rigid_circle);
  r.translation     = "0.2*t; 0";
  r.rotation        = "pi/2*t";
  r.rotation_center = {1., 2., 0.};
  RigidMaster<2> spinning(r, "pair");
  EXPECT_EQ(
    spinning.passage_depth(Point<2>(1., 2.55), 0., Point<2>(1., 2.55), 1., 0.),
    0.);
  p.rotation    = "0";
  p.translation = "0; -3*t; 0";
  RigidMaster<3> cylinder(p, "pair");
  EXPECT_NEAR(cylinder.passage_depth(
                Point<3>(1.2, 0., -4.), 0., Point<3>(1.2, 0., 9.), 1., 0.),
              0.3,
              1e-12);
  auto sphere_p        = p;
  sphere_p.master_type = MasterType::rigid_sphere;
  RigidMaster<3> sphere(sphere_p, "pair");
  // 0.2 beside the centre line in x and 0.1 in z.
  EXPECT_NEAR(sphere.passage_depth(
                Point<3>(1.2, 0., 0.1), 0., Point<3>(1.2, 0., 0.1), 1., 0.),
              0.5 - std::sqrt(0.05),
              1e-12);
  auto plane_p        = rigid(MasterType::rigid_plane);
  plane_p.translation = "0; -3*t";
  RigidMaster<2> plane(plane_p, "pair");
  EXPECT_EQ(
    plane.passage_depth(Point<2>(1.2, 0.), 0., Point<2>(1.2, 0.), 1., 0.), 0.);
  auto hole_p        = rigid(MasterType::rigid_circle, true);
  hole_p.translation = "0; -3*t";
  RigidMaster<2> hole(hole_p, "pair");
  EXPECT_EQ(
    hole.passage_depth(Point<2>(1.2, 0.), 0., Point<2>(1.2, 0.), 1., 0.), 0.);
}

// P1.4: a rotation about an axis other than z in 3D. A cylinder through
// (1, 2, 0) along z, turned by 90 degrees about the x axis through (1, 2,
// 0): its axis lies along -y, so a point's gap is its distance from the
// line {x = 1, z = 0} minus the radius, whatever its y; move() carries a
// point of the master along the same rigid motion.
TEST(RigidMaster, RotationAboutAnyAxisIn3D)
{
  auto p            = rigid(MasterType::rigid_circle);
  p.rotation        = "pi/2*t";
  p.rotation_center = {1., 2., 0.};
  p.rotation_axis   = {{1., 0., 0.}};
  RigidMaster<3> m(p, "pair");
  m.set_time(1.);
  for (const double y : {-3., 2., 10.})
    {
      const auto q = m.project(Point<3>(1., y, 0.8));
      EXPECT_NEAR(q.gap, 0.3, 1e-12) << y;
      EXPECT_NEAR(q.normal[2], 1., 1e-12) << y;
      EXPECT_NEAR(q.curvature[1][1], 0., 1e-12)
        << "no curvature along the axis";
    }
  // The point (1, 2, 1) of the reference master (on its axis, z = 1) goes
  // to (1, 1, 0) (z turns into -y about x).
  const auto x = m.move(Point<3>(1., 2., 1.), 0., 1.);
  EXPECT_NEAR((x - Point<3>(1., 1., 0.)).norm(), 0., 1e-12);
  // From a turned state on: the way back (-theta(0.5)) and forward again
  // gives the same point as going from the reference.
  const auto half = m.move(Point<3>(1., 2., 1.), 0., 0.5);
  EXPECT_NEAR((m.move(half, 0.5, 1.) - x).norm(), 0., 1e-12);
  EXPECT_GT((half - x).norm(), 0.5) << "half-way is a different point";
  // A plane normal along y turned about x by 90 degrees: along z.
  auto plane          = rigid(MasterType::rigid_plane);
  plane.rotation      = "pi/2*t";
  plane.rotation_axis = {{2., 0., 0.}}; // normalized
  RigidMaster<3> r(plane, "pair");
  r.set_time(1.);
  EXPECT_NEAR(r.project(Point<3>(0., 0., 3.)).normal[2], 1., 1e-12);
}

TEST(RigidMaster, NormalUndefinedAtTheCenterIsReported)
{
  RigidMaster<2> m(rigid(MasterType::rigid_circle), "pair");
  EXPECT_THROW(m.project(Point<2>(1., 2.)), UndefinedNormal);
}

namespace
{
  std::string
  contact_scene(const bool         three,
                const std::string &master,
                const std::string &enforcement)
  {
    std::ostringstream s;
    s << "set Dimension = " << (three ? 3 : 2)
      << "\nset Analysis type = " << (three ? "3d" : "plane strain")
      << "\nset Boundary conditions = hold\nset Contact pairs = pair\n"
      << "subsection Body body\n  subsection Block\n    set Lower corner = "
      << (three ? "0, 0, 0" : "0, 0")
      << "\n    set Upper corner = " << (three ? "1, 1, 1" : "1, 1")
      << "\n    set Subdivisions = " << (three ? "2, 2, 2" : "3, 2")
      << "\n  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = body.bottom\n  set Type = fixed\nend\n"
      << "subsection Contact pair pair\n  set Slave = body.top\n  set Master = "
      << master << "\n  set Enforcement = " << enforcement
      << "\n  subsection Rigid master\n    set Point = "
      << (master == "rigid plane" ? (three ? "0.5, 1.0, 0.5" : "0.5, 1.0") :
                                    (three ? "0.5, 1.95, 0.5" : "0.5, 1.95"))
      << "\n    set Normal = " << (three ? "0.1, -1, 0.2" : "0.1, -1")
      << "\n    set Radius = 1.0\n  end\nend\n";
    return s.str();
  }

  template <int dim>
  void
  check_contact_jacobian(const std::string &master,
                         const std::string &enforcement)
  {
    const Scene scene = Scene::read(
      glide_test::write_file("contact_" + master.substr(6) + enforcement +
                               std::to_string(dim) + ".prm",
                             contact_scene(dim == 3, master, enforcement)));
    TimerOutput     timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    Elasticity<dim> e(scene, MPI_COMM_WORLD, timer);
    e.setup();
    Contact<dim> contact(scene, e, MPI_COMM_WORLD);
    contact.setup(e.get_dof_handler().n_dofs());
    e.setup_system(contact.owned_multipliers(),
                   [&](DynamicSparsityPattern &dsp) {
                     contact.add_sparsity(dsp);
                   });

    // A state in which the master penetrates some slave nodes and not
    // others: the tilted plane passes through (0.5, 1) on the top of the
    // block; the circle or sphere (radius 1 about (0.5, 1.95)) dips 0.05
    // into it around x = 0.5.
    VectorType U, v;
    glide_test::random_contact_state(e, contact, U, v, 7, 0.02, 0.05);
    contact.set_time(0.);

    const auto [err, ref] =
      glide_test::contact_jacobian_error(e, contact, U, v);
    EXPECT_GT(ref, 0.) << master << " " << enforcement;
    EXPECT_LT(err, 1e-6 * ref)
      << master << " " << enforcement << " " << dim << "D";
    // Both kinds of node occur for hard contact: the test covers the active
    // and the inactive branch of the complementarity function.
    const auto stats = contact.statistics(U);
    ASSERT_EQ(stats[0].first, "contact_pair_active");
    EXPECT_GT(std::stoi(stats[0].second), 0) << "some nodes are closed";
  }
} // namespace

TEST(Contact, JacobianMatchesFiniteDifferences2D)
{
  for (const char *master : {"rigid plane", "rigid circle"})
    for (const char *enforcement : {"hard", "penalty"})
      check_contact_jacobian<2>(master, enforcement);
}

TEST(Contact, JacobianMatchesFiniteDifferences3D)
{
  for (const char *master : {"rigid plane", "rigid circle", "rigid sphere"})
    for (const char *enforcement : {"hard", "penalty"})
      check_contact_jacobian<3>(master, enforcement);
}

TEST(Contact, SmoothingFractionOutOfRangeNamesThePair)
{
  std::string text = contact_scene(false, "rigid plane", "hard");
  text.replace(text.find("  set Enforcement"),
               0,
               "  set Smoothing fraction = 0.5\n");
  try
    {
      Scene::read(glide_test::write_file("smoothing_range.prm", text));
      FAIL() << "no error";
    }
  catch (const InputError &e)
    {
      const std::string m = e.what();
      EXPECT_NE(m.find("contact pair 'pair'"), std::string::npos) << m;
      EXPECT_NE(m.find("0 <= f < 0.5"), std::string::npos) << m;
    }
}

TEST(Contact, SlaveThatIsItsOwnMaster)
{
  std::string text = contact_scene(false, "body.top", "hard");
  try
    {
      Scene::read(glide_test::write_file("self_contact.prm", text));
      FAIL() << "no error";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("both slave and master"),
                std::string::npos)
        << e.what();
    }
}

TEST(Contact, UnknownSlaveSurfaceListsTheSurfaces)
{
  std::string text = contact_scene(false, "rigid plane", "hard");
  text.replace(text.find("body.top"), 8, "body.lid");
  const Scene scene =
    Scene::read(glide_test::write_file("unknown_slave.prm", text));
  TimerOutput   timer(MPI_COMM_WORLD,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  Elasticity<2> e(scene, MPI_COMM_WORLD, timer);
  e.setup();
  Contact<2> contact(scene, e, MPI_COMM_WORLD);
  try
    {
      contact.setup(e.get_dof_handler().n_dofs());
      FAIL() << "no error";
    }
  catch (const InputError &err)
    {
      const std::string m = err.what();
      EXPECT_NE(m.find("Contact pair pair/Slave"), std::string::npos) << m;
      EXPECT_NE(m.find("body.top"), std::string::npos) << m;
    }
}

TEST(Contact, ActiveSetCyclingIsDetectedAndNamesTheNodes)
{
  // R16.1: the driver's monitor, not the residual, detects cycling. A node
  // whose state flips at every Newton iterate (here: its contact force
  // toggled between 0 and a large value while the master is away, so it is
  // alternately closed and open) is reported after more than 4 switches,
  // with its position; after reset() (a new solve) counting starts afresh.
  std::string text = contact_scene(false, "rigid plane", "hard");
  text.replace(text.find("0.5, 1.0\n"),
               9,
               "0.5, 3.0\n"); // the plane far above: all open
  const Scene scene = Scene::read(glide_test::write_file("cycling.prm", text));
  TimerOutput timer(MPI_COMM_WORLD,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  Elasticity<2> e(scene, MPI_COMM_WORLD, timer);
  e.setup();
  Contact<2> contact(scene, e, MPI_COMM_WORLD);
  contact.setup(e.get_dof_handler().n_dofs());
  e.setup_system(contact.owned_multipliers(), [&](DynamicSparsityPattern &dsp) {
    contact.add_sparsity(dsp);
  });
  VectorType          U(e.locally_owned(), MPI_COMM_WORLD);
  ActiveSetMonitor<2> monitor;
  const auto          iterate = [&](const bool closed) {
    U = 0;
    for (const auto i : contact.owned_multipliers())
      U[i] = closed ? 1e6 : 0.;
    U.compress(VectorOperation::insert);
    monitor.record(contact.status(U));
  };
  for (unsigned int k = 0; k < 5; ++k)
    {
      iterate(k % 2 == 0);
      EXPECT_EQ(monitor.cycling(MPI_COMM_WORLD), "") << "iterate " << k;
    }
  iterate(false); // the fifth switch
  const std::string nodes = monitor.cycling(MPI_COMM_WORLD);
  EXPECT_NE(nodes.find("(0 1)"), std::string::npos) << nodes;
  monitor.reset();
  iterate(true);
  EXPECT_EQ(monitor.cycling(MPI_COMM_WORLD), "");
}

TEST(Contact, StabilizationOnlyInTheJacobianOfOpenNodesNearTheMaster)
{
  // Contact::stabilization_weight(): with every slave node open and within
  // one facet of a flat rigid master, the Jacobian gains a positive
  // semidefinite term s_J c (1 - g/h)^2 n n^T on the slave rows, and the
  // residual is unchanged (it is zero: open nodes carry no force); with
  // the master farther than a facet away, nothing is added. Scaled by the
  // factor of set_jacobian_stabilization().
  for (const double height : {1.1, 2.0})
    {
      std::string        text = contact_scene(false, "rigid plane", "hard");
      std::ostringstream point;
      point << "0.5, " << height << "\n";
      text.replace(text.find("0.5, 1.0\n"), 9, point.str());
      text.replace(text.find("0.1, -1\n"), 8, "0, -1\n");
      glide_test::ContactFixture<2> s(text, "stabilization.prm");
      VectorType U(s.e.locally_owned(), MPI_COMM_WORLD), F(U), Fon(U);
      MatrixType on, off, scaled;
      on.reinit(s.e.matrix_pattern());
      off.reinit(s.e.matrix_pattern());
      scaled.reinit(s.e.matrix_pattern());
      s.contact.assemble(U, &Fon, &on);
      s.contact.set_jacobian_stabilization(false);
      s.contact.assemble(U, &F, &off);
      // The driver's scaled springs (once the active set has settled):
      // the added term is proportional to the factor.
      s.contact.set_jacobian_stabilization(0.25);
      s.contact.assemble(U, nullptr, &scaled);
      EXPECT_EQ(Fon.linfty_norm(), 0.);
      EXPECT_EQ(F.linfty_norm(), 0.);
      on.add(-1., off);
      scaled.add(-1., off);
      scaled.add(-0.25, on);
      EXPECT_LE(scaled.frobenius_norm(), 1e-12 * on.frobenius_norm())
        << "master at " << height;
      // v = a uniform motion: v^T (J_on - J_off) v > 0 near the master.
      VectorType v(U), Dv(U);
      for (const auto i : s.e.displacement_owned())
        v[i] = 1.;
      v.compress(VectorOperation::insert);
      on.vmult(Dv, v);
      if (height < 1.5)
        EXPECT_GT(Dv * v, 0.) << "master at " << height;
      else
        EXPECT_EQ(on.frobenius_norm(), 0.) << "master at " << height;
    }
}

namespace
{
  /// R16.1 for one scene: F(U), then the Jacobian at U, then F(U) again,
  /// and once more after status() and needs_new_pattern() (what the driver
  /// calls between residuals): identical vectors, bit for bit.
  template <int dim>
  void
  expect_pure_residual(const std::string &text, const std::string &tag)
  {
    glide_test::ContactFixture<dim> s(text, "pure_" + tag + ".prm");
    VectorType                      U, v;
    glide_test::random_contact_state(s.e, s.contact, U, v, 11, 0.01, 0.02);
    s.contact.set_time(0.);
    MatrixType J;
    J.reinit(s.e.matrix_pattern());
    VectorType F1(s.e.locally_owned(), MPI_COMM_WORLD), F2(F1), F3(F1);
    s.contact.assemble(U, &F1, nullptr);
    s.contact.assemble(U, nullptr, &J);
    s.contact.assemble(U, &F2, nullptr);
    const auto status = s.contact.status(U);
    s.contact.needs_new_pattern(U);
    s.contact.assemble(U, nullptr, &J);
    s.contact.assemble(U, &F3, nullptr);
    EXPECT_GT(F1.l2_norm(), 0.) << tag;
    F2 -= F1;
    F3 -= F1;
    EXPECT_EQ(F2.linfty_norm(), 0.) << tag;
    EXPECT_EQ(F3.linfty_norm(), 0.) << tag;
    // The history committed after a converged step (positions,
    // projections, offsets, slip) is not read by these frictionless
    // residuals: committing at U changes nothing at U.
    s.contact.commit_step(U, 0., 0.);
    VectorType F4(F1);
    F4 = 0.;
    s.contact.assemble(U, &F4, nullptr);
    F4 -= F1;
    EXPECT_EQ(F4.linfty_norm(), 0.) << tag;
    unsigned int closed = 0;
    for (const auto &st : status)
      closed += st.closed ? 1 : 0;
    EXPECT_GT(closed, 0u) << tag << ": some nodes closed";
  }

  /// Two stacked blocks, the upper one's bottom the slave surface on the
  /// lower one's top, with the contact pair settings @p pair.
  std::string
  two_blocks(const std::string &pair)
  {
    return "set Dimension = 2\nset Analysis type = plane strain\n"
           "set Bodies = lower, upper\nset Boundary conditions = hold\n"
           "set Contact pairs = pair\n"
           "subsection Body lower\n  subsection Block\n"
           "    set Lower corner = 0, -1\n    set Upper corner = 1, 0\n"
           "    set Subdivisions = 4, 2\n  end\nend\n"
           "subsection Body upper\n  subsection Block\n"
           "    set Lower corner = 0.05, 0\n    set Upper corner = 0.95, 0.5\n"
           "    set Subdivisions = 3, 2\n  end\nend\n"
           "subsection Boundary condition hold\n  set Surface = lower.bottom\n"
           "  set Type = fixed\nend\n"
           "subsection Contact pair pair\n  set Slave = upper.bottom\n"
           "  set Master = lower.top\n" +
           pair + "end\n";
  }
} // namespace

TEST(Contact, ResidualIsAFunctionOfTheIterate)
{
  // R16.1, for every formulation and enforcement: node to surface against
  // analytical rigid masters (hard, penalty), finite sliding on a
  // deformable master (faceted f = 0, smoothed f = 0.2), small-sliding
  // node to surface and surface to surface, mortar (hard, penalty), in 2D
  // and 3D where they exist.
  for (const char *master : {"rigid plane", "rigid circle"})
    for (const char *enforcement : {"hard", "penalty"})
      {
        expect_pure_residual<2>(contact_scene(false, master, enforcement),
                                std::string(master).substr(6) + enforcement);
        expect_pure_residual<3>(contact_scene(true, master, enforcement),
                                std::string(master).substr(6) + enforcement +
                                  "3d");
      }
  for (const char *pair : {"  set Smoothing fraction = 0\n",
                           "  set Smoothing fraction = 0.2\n",
                           "  set Smoothing fraction = 0.2\n"
                           "  set Enforcement = penalty\n",
                           "  set Sliding = small\n",
                           "  set Sliding = small\n"
                           "  set Formulation = surface to surface\n",
                           "  set Formulation = mortar\n",
                           "  set Formulation = mortar\n"
                           "  set Enforcement = penalty\n"})
    expect_pure_residual<2>(two_blocks(pair),
                            "blocks" +
                              std::to_string(std::string(pair).size()));
}

// Issue 12: the formulation of a pair is chosen by name from 'Formulation'
// and 'Sliding', and the log names it with its enforcement.
TEST(Contact, FormulationsAreChosenByName)
{
  const std::vector<std::pair<std::string, std::string>> cases{
    {"", "node to surface, finite sliding"},
    {"  set Enforcement = penalty\n", "node to surface, finite sliding"},
    // Small sliding in a geometrically linear scene is infinitesimal.
    {"  set Sliding = small\n", "node to surface, infinitesimal sliding"},
    {"  set Sliding = small\n  set Formulation = surface to surface\n",
     "surface to surface, infinitesimal sliding"},
    {"  set Formulation = mortar\n", "mortar, finite sliding"}};
  for (const auto &[pair, name] : cases)
    {
      glide_test::ContactFixture<2> s(two_blocks(pair), "names.prm");
      const auto                    effects = s.contact.active_effects();
      ASSERT_EQ(effects.size(), 1u);
      EXPECT_NE(effects[0].find("(" + name), std::string::npos) << effects[0];
      const std::string enforcement =
        pair.find("penalty") != std::string::npos ? "penalty" : "hard";
      // The roles are named as such (the master's name alone, where the
      // slave's belonged, read as if it were the slave).
      EXPECT_NE(effects[0].find(", slave upper.bottom with 4 nodes, master "
                                "lower.top, " +
                                enforcement + ")"),
                std::string::npos)
        << effects[0];
    }
}

// R13.1: local tangent directions by the documented convention, an
// orthonormal frame with the normal.
TEST(Contact, LocalTangentDirections)
{
  Tensor<1, 2> n2;
  n2[0]         = 0.6;
  n2[1]         = 0.8;
  const auto t2 = contact_tangents<2>(n2);
  EXPECT_NEAR(t2[0][0], -0.8, 1e-15);
  EXPECT_NEAR(t2[0][1], 0.6, 1e-15);
  for (const auto &n : {Tensor<1, 3>({0., 1., 0.}),
                        Tensor<1, 3>({0.48, 0.6, 0.64}),
                        Tensor<1, 3>({1., 0., 0.})})
    {
      const auto t = contact_tangents<3>(n);
      EXPECT_NEAR(t[0] * n, 0., 1e-15);
      EXPECT_NEAR(t[1] * n, 0., 1e-15);
      EXPECT_NEAR(t[0] * t[1], 0., 1e-15);
      EXPECT_NEAR(t[0].norm(), 1., 1e-15);
      EXPECT_NEAR(t[1].norm(), 1., 1e-15);
      // Right-handed: t1 x t2 = n.
      EXPECT_NEAR((cross_product_3d(t[0], t[1]) - n).norm(), 0., 1e-15);
      if (n[0] < 0.5)
        EXPECT_GT(t[0][0], 0.) << "t1 follows the global x axis";
      else
        EXPECT_NEAR(t[0][2], 1., 1e-15) << "x along n: t1 follows z";
    }
}
