// Unit tests of mortar contact (issue 14, R14.1-R14.4, R14.7). Why the
// expected answers are right:
// - the contact Jacobian must be the derivative of the contact residual
//   (R14.4): central finite differences, on curved and flat, matching and
//   non-matching surfaces, with slave facets partly outside the master, for
//   degree 1 and 2, hard and penalty, plane strain and axisymmetric;
// - the dual basis is biorthogonal (R14.1): on a slave surface that the
//   master covers entirely, D_jj is the node's tributary area int N_j dA,
//   and since the master's shape functions sum to one, sum_m M_jm = D_jj;
// - a flat master parallel to a flat slave at distance d has the weighted
//   gap g~_j = d D_jj exactly (R14.2: a flat interface is integrated
//   exactly), whatever the meshes.
#include <glide/contact/contact.h>
#include <glide/contact/mortar.h>

#include "test_helpers.h"
#include <gtest/gtest.h>

#include <sstream>

using namespace dealii;
using namespace glide;

namespace
{
  /// Two stacked blocks: the upper one [x0, x1] x [gap, gap + 0.5] (its
  /// bottom the slave, n_upper cells across) on the lower one [0, 1] x [-1,
  /// 0] (its top the master, n_lower cells across).
  std::string
  stacked_blocks(const double       x0,
                 const double       x1,
                 const double       gap,
                 const unsigned int n_upper,
                 const unsigned int n_lower,
                 const std::string &pair,
                 const unsigned int degree = 1)
  {
    std::ostringstream s;
    s << "set Dimension = 2\nset Analysis type = plane strain\n"
      << "subsection Discretization\n  set Element degree = " << degree
      << "\nend\nset Bodies = lower, upper\nset Boundary conditions = hold\n"
      << "set Contact pairs = pair\n"
      << "subsection Body lower\n  subsection Block\n"
      << "    set Lower corner = 0, -1\n    set Upper corner = 1, 0\n"
      << "    set Subdivisions = " << n_lower << ", 2\n  end\nend\n"
      << "subsection Body upper\n  subsection Block\n"
      << "    set Lower corner = " << x0 << ", " << gap
      << "\n    set Upper corner = " << x1 << ", " << gap + 0.5
      << "\n    set Subdivisions = " << n_upper << ", 2\n  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = lower.bottom\n"
      << "  set Type = fixed\nend\n"
      << "subsection Contact pair pair\n  set Slave = upper.bottom\n"
      << "  set Master = lower.top\n  set Formulation = mortar\n"
      << pair << "end\n";
    return s.str();
  }

  /// A ball (hertz mesh, radius 1) dipping 0.05 into a block [0, 1]^2
  /// (axisymmetric: the block's left side on the axis); @p ball_slave
  /// makes the ball's curved surface the slave.
  std::string
  ball_on_block(const std::string &analysis,
                const bool         ball_slave,
                const unsigned int degree,
                const std::string &enforcement)
  {
    const bool         axi = analysis == "axisymmetric";
    std::ostringstream s;
    s << "set Dimension = 2\nset Analysis type = " << analysis
      << "\nsubsection Discretization\n  set Element degree = " << degree
      << "\nend\nset Bodies = block, ball\n"
      << "set Boundary conditions = hold, top\nset Contact pairs = pair\n"
      << "subsection Body block\n  subsection Block\n"
      << "    set Lower corner = 0, 0\n    set Upper corner = 1, 1\n"
      << "    set Subdivisions = 7, 2\n  end\nend\n"
      << "subsection Body ball\n  set Mesh = hertz\n"
      << "  subsection Round shapes\n    set Center = "
      << (axi ? "0, 1.95" : "0.5, 1.95") << "\n    set Radius = 1\n  end\n"
      << "  subsection Refinement\n    set Global refinements = 2\n  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = block.bottom\n"
      << "  set Type = fixed\nend\n"
      << "subsection Boundary condition top\n  set Surface = ball.flat\n"
      << "  set Type = fixed\nend\n"
      << "subsection Contact pair pair\n  set Slave = "
      << (ball_slave ? "ball.curved" : "block.top")
      << "\n  set Master = " << (ball_slave ? "block.top" : "ball.curved")
      << "\n  set Formulation = mortar\n  set Enforcement = " << enforcement
      << "\nend\n";
    return s.str();
  }

  /// The contact Jacobian of the scene @p text at a random state near the
  /// reference configuration against central finite differences.
  template <int dim = 2>
  void
  expect_exact_jacobian(const std::string &text,
                        const std::string &tag,
                        const double       displacement,
                        const bool         hanging = false)
  {
    glide_test::ContactFixture<dim> s(text, "mortar_fd_" + tag + ".prm");
    VectorType                      U, v;
    glide_test::random_contact_state(
      s.e, s.contact, U, v, 3, displacement, 0.02);
    if (s.contact.needs_new_pattern(U))
      s.e.setup_system(s.contact.owned_multipliers(),
                       [&](DynamicSparsityPattern &dsp) {
                         s.contact.add_sparsity(dsp);
                       });
    const auto [err, ref] =
      glide_test::contact_jacobian_error(s.e, s.contact, U, v, 1e-7);
    EXPECT_GT(ref, 0.) << tag;
    EXPECT_LT(err, 1e-6 * ref) << tag;
    // Both branches of the complementarity function occur.
    const auto   stats  = s.contact.statistics(U);
    const int    active = std::stoi(stats[0].second);
    unsigned int n      = 0;
    for (const auto &st : s.contact.status(U))
      n += st.closed ? 0 : 1;
    EXPECT_GT(active, 0) << tag << ": some nodes closed";
    EXPECT_GT(n, 0u) << tag << ": some nodes open";
    if (hanging)
      {
        // Closed slave nodes with hanging nodes merged into them.
        const auto  &nodes  = s.contact.slave_nodes(0);
        const auto   status = s.contact.status(U);
        unsigned int merged = 0, any = 0;
        for (unsigned int i = 0; i < nodes.size(); ++i)
          {
            merged += !nodes[i].hanging.empty() && status[i].closed ? 1 : 0;
            any += !nodes[i].hanging.empty() ? 1 : 0;
          }
        EXPECT_GT(any, 0u) << tag << ": nodes with hanging nodes";
        EXPECT_GT(merged, 0u) << tag << ": closed nodes with hanging nodes";
      }
  }

  const Mortar<2> &
  mortar_of(const glide_test::ContactFixture<2> &s)
  {
    const auto *m =
      dynamic_cast<const Mortar<2> *>(&s.contact.formulation_of(0));
    EXPECT_NE(m, nullptr);
    return *m;
  }
} // namespace

// R14.4: the consistent linearization (variation of the segments, of the
// slave normals, of the projections and of the dual basis).
TEST(Mortar, JacobianMatchesFiniteDifferences)
{
  for (const char *enforcement : {"hard", "penalty"})
    {
      const std::string e(enforcement);
      // Curved master over a flat slave, and curved slave on a flat master.
      expect_exact_jacobian(ball_on_block("plane strain", false, 1, e),
                            "ball_master_" + e,
                            0.01);
      expect_exact_jacobian(ball_on_block("plane strain", true, 1, e),
                            "ball_slave_" + e,
                            0.01);
      // Axisymmetric, the slave ending on the axis.
      expect_exact_jacobian(ball_on_block("axisymmetric", false, 1, e),
                            "axi_" + e,
                            0.01);
      // Degree 2, curved facets on both sides.
      expect_exact_jacobian(ball_on_block("plane strain", true, 2, e),
                            "quadratic_" + e,
                            0.005);
      // Flat, non-matching, the slave's end facets partly outside the
      // master (the upper block overhangs the lower one on the right).
      expect_exact_jacobian(
        stacked_blocks(
          0.55, 1.25, -0.01, 5, 3, "  set Enforcement = " + e + "\n"),
        "overhang_" + e,
        0.005);
    }
}

// R14.1, R14.2: biorthogonality and exact integration on flat surfaces.
TEST(Mortar, DualBasisAndExactWeightedGapOnFlatSurfaces)
{
  for (const unsigned int degree : {1u, 2u})
    for (const auto &[n_upper, n_lower] :
         std::vector<std::pair<unsigned int, unsigned int>>{{5, 5},
                                                            {7, 5},
                                                            {3, 8}})
      {
        const double                  d = 0.0123;
        glide_test::ContactFixture<2> s(
          stacked_blocks(0., 1., d, n_upper, n_lower, "", degree),
          "mortar_flat.prm");
        VectorType  U(s.e.locally_owned(), MPI_COMM_WORLD);
        const auto &m     = mortar_of(s);
        const auto &nodes = s.contact.slave_nodes(0);
        m.move(U);
        ASSERT_EQ(nodes.size(), degree * n_upper + 1);
        for (unsigned int i = 0; i < nodes.size(); ++i)
          {
            const auto t = m.terms(i);
            EXPECT_NEAR(t.weight, nodes[i].area, 1e-14)
              << "D_jj = int N_j dA, degree " << degree;
            double sum = 0.;
            for (const double x : t.M)
              sum += x;
            EXPECT_NEAR(sum, t.weight, 1e-14) << "sum_m M_jm = D_jj";
            EXPECT_NEAR(t.weighted_gap, d * t.weight, 1e-15)
              << "weighted gap of a uniform gap d";
            EXPECT_NEAR(t.normal[0], 0., 1e-15);
            EXPECT_NEAR(t.normal[1], -1., 1e-15) << "outward slave normal";
          }
      }
}

// R14.7 and the input rules: mortar is finite sliding on a master surface
// of a body, 2D so far; anything else is refused with a message that names
// the parameter.
TEST(Mortar, RefusedWhereItDoesNotApply)
{
  const auto refused = [](const std::string &text, const std::string &what) {
    try
      {
        glide_test::ContactFixture<2> s(text, "mortar_refused.prm");
        ADD_FAILURE() << "accepted: " << what;
      }
    catch (const std::exception &e)
      {
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos)
          << e.what();
      }
  };
  refused(stacked_blocks(0., 1., 0., 3, 3, "  set Sliding = small\n"),
          "'Sliding = finite'");
  std::string rigid = stacked_blocks(0., 1., 0., 3, 3, "");
  rigid.replace(rigid.find("set Master = lower.top"),
                std::string("set Master = lower.top").size(),
                "set Master = rigid plane");
  refused(rigid, "master surface of a body");
}

// ---------------------------------------------------------------------------
// 3D (R14.2 polygon clipping, R14.4 linearization; Popp, Gitterle, Gee and
// Wall 2010). Why the expected answers are right: as in 2D above. The
// Jacobian must be the derivative of the residual whatever the geometry
// (the clip polygons, auxiliary planes, projections, normals and dual
// basis are all differentiated), so it is checked against central
// differences on a curved master and on a curved (warped) slave, on flat
// non-matching blocks with the slave overhanging the master, and with
// symmetry planes at the slave's boundary. On flat parallel surfaces the
// auxiliary plane is the slave facet's plane, the area ratio is one and
// the integrands are polynomials of degree <= 5 in the plane on
// rectangular facets, so D_jj, M_jm and the weighted gap are exact.
namespace
{
  /// Two stacked blocks in 3D: the upper one [x0, x1] x [gap, gap + 0.5] x
  /// [z0, z1] (its bottom the slave, n_upper x n_upper cells across) on the
  /// lower one [0, 1] x [-1, 0] x [0, 1] (its top the master, n_lower_x x
  /// n_lower_z cells across).
  std::string
  stacked_blocks_3d(const double       x0,
                    const double       x1,
                    const double       z0,
                    const double       z1,
                    const double       gap,
                    const unsigned int n_upper,
                    const unsigned int n_lower_x,
                    const unsigned int n_lower_z,
                    const std::string &pair)
  {
    std::ostringstream s;
    s << "set Dimension = 3\nset Analysis type = 3d\n"
      << "set Bodies = lower, upper\nset Boundary conditions = hold\n"
      << "set Contact pairs = pair\n"
      << "subsection Body lower\n  subsection Block\n"
      << "    set Lower corner = 0, -1, 0\n    set Upper corner = 1, 0, 1\n"
      << "    set Subdivisions = " << n_lower_x << ", 1, " << n_lower_z
      << "\n  end\nend\n"
      << "subsection Body upper\n  subsection Block\n"
      << "    set Lower corner = " << x0 << ", " << gap << ", " << z0
      << "\n    set Upper corner = " << x1 << ", " << gap + 0.5 << ", " << z1
      << "\n    set Subdivisions = " << n_upper << ", 1, " << n_upper
      << "\n  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = lower.bottom\n"
      << "  set Type = fixed\nend\n"
      << "subsection Contact pair pair\n  set Slave = upper.bottom\n"
      << "  set Master = lower.top\n  set Formulation = mortar\n"
      << pair << "end\n";
    return s.str();
  }

  /// The sphere octant (hertz mesh, radius 1, coarse: curved, warped
  /// facets) dipping 0.05 into a block [0, 1]^3; @p ball_slave makes the
  /// sphere's curved surface the slave; @p symmetry puts XSYMM and ZSYMM on
  /// the block's sides x = 0 and z = 0 (the slave's boundary nodes there
  /// then carry them: nodal normals projected into the symmetry planes).
  std::string
  ball_on_block_3d(const bool         ball_slave,
                   const bool         symmetry,
                   const std::string &enforcement,
                   const bool         refined = false)
  {
    std::ostringstream s;
    s << "set Dimension = 3\nset Analysis type = 3d\n"
      << "set Bodies = block, ball\n"
      << "set Boundary conditions = hold, top" << (symmetry ? ", sx, sz" : "")
      << "\nset Contact pairs = pair\n"
      << "subsection Body block\n  subsection Block\n"
      << "    set Lower corner = 0, 0, 0\n    set Upper corner = 1, 1, 1\n"
      << "    set Subdivisions = 4, 1, 4\n  end\n"
      // Locally refined slave surfaces: hanging nodes in the contact zone.
      << (refined && !ball_slave ?
            "  subsection Refinement\n    set Local refinements = 1\n"
            "    set Refinement point = 0.05, 1, 0.05\n"
            "    set Refinement radius = 0.2\n  end\n" :
            "")
      << "end\n"
      << "subsection Body ball\n  set Mesh = hertz\n"
      << "  subsection Round shapes\n    set Center = "
      << (symmetry ? "0, 1.95, 0" : "0.05, 1.95, 0.05")
      << "\n    set Radius = 1\n  end\n"
      << "  subsection Refinement\n    set Global refinements = 1\n"
      << (refined && ball_slave ? "    set Local refinements = 1\n"
                                  "    set Refinement radius = 0.25\n" :
                                  "")
      << "  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = block.bottom\n"
      << "  set Type = fixed\nend\n"
      << "subsection Boundary condition top\n  set Surface = ball.flat\n"
      << "  set Type = fixed\nend\n";
    if (symmetry)
      s << "subsection Boundary condition sx\n  set Surface = block.left, "
           "ball.x0\n  set Type = XSYMM\nend\n"
        << "subsection Boundary condition sz\n  set Surface = block.back, "
           "ball.z0\n  set Type = ZSYMM\nend\n";
    s << "subsection Contact pair pair\n  set Slave = "
      << (ball_slave ? "ball.curved" : "block.top")
      << "\n  set Master = " << (ball_slave ? "block.top" : "ball.curved")
      << "\n  set Formulation = mortar\n  set Enforcement = " << enforcement
      << "\nend\n";
    return s.str();
  }

} // namespace

// R14.4 in 3D: the consistent linearization through the clipping.
TEST(Mortar, JacobianMatchesFiniteDifferences3D)
{
  for (const char *enforcement : {"hard", "penalty"})
    {
      const std::string e(enforcement);
      // Curved master over a flat slave.
      expect_exact_jacobian<3>(ball_on_block_3d(false, false, e),
                               "ball_master_3d_" + e,
                               0.01);
      // Curved, warped slave facets on a flat master.
      expect_exact_jacobian<3>(ball_on_block_3d(true, false, e),
                               "ball_slave_3d_" + e,
                               0.01);
      // Symmetry planes at the slave's boundary.
      expect_exact_jacobian<3>(ball_on_block_3d(false, true, e),
                               "ball_symmetry_3d_" + e,
                               0.01);
      // Locally refined slave surfaces, flat and curved: the terms of the
      // hanging nodes in the contact zone are added to their parents'
      // (hard: some of those parents closed; measured 2 of 5 and 2 of 3).
      expect_exact_jacobian<3>(ball_on_block_3d(false, false, e, true),
                               "ball_master_refined_3d_" + e,
                               0.01,
                               e == "hard");
      expect_exact_jacobian<3>(ball_on_block_3d(true, false, e, true),
                               "ball_slave_refined_3d_" + e,
                               0.01,
                               e == "hard");
      // Flat, non-matching, the slave overhanging the master on two sides
      // (its facets there partly or wholly outside: the nodes beyond the
      // master's edges have no constraint and count as open).
      expect_exact_jacobian<3>(stacked_blocks_3d(0.45,
                                                 1.45,
                                                 0.3,
                                                 1.3,
                                                 -0.005,
                                                 3,
                                                 4,
                                                 3,
                                                 "  set Enforcement = " + e +
                                                   "\n"),
                               "overhang_3d_" + e,
                               0.005);
    }
}

// R14.1, R14.2 in 3D: biorthogonality and exact integration on flat,
// non-matching surfaces (4 x 4 over 5 x 5 and 3 x 3 over 4 x 5 cells).
TEST(Mortar, DualBasisAndExactWeightedGapOnFlatSurfaces3D)
{
  for (const auto &[n_upper, n_x, n_z] :
       std::vector<std::array<unsigned int, 3>>{{{4, 5, 5}}, {{3, 4, 5}}})
    {
      const double                  d = 0.0123;
      glide_test::ContactFixture<3> s(
        stacked_blocks_3d(0., 1., 0., 1., d, n_upper, n_x, n_z, ""),
        "mortar_flat_3d.prm");
      VectorType  U(s.e.locally_owned(), MPI_COMM_WORLD);
      const auto *m =
        dynamic_cast<const Mortar<3> *>(&s.contact.formulation_of(0));
      ASSERT_NE(m, nullptr);
      const auto &nodes = s.contact.slave_nodes(0);
      m->move(U);
      ASSERT_EQ(nodes.size(), (n_upper + 1) * (n_upper + 1));
      double total = 0.;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const auto t = m->terms(i);
          // Tributary area of a node of a uniform n x n grid on the unit
          // square: h^2 times 1/4 per facet at the node.
          const double h = 1. / n_upper;
          unsigned int k = 0;
          for (unsigned int c : {0u, 2u})
            k += (std::abs(nodes[i].X[c]) < 1e-12 ||
                  std::abs(nodes[i].X[c] - 1.) < 1e-12) ?
                   1 :
                   0;
          const double tributary = h * h * (k == 0 ? 1. : k == 1 ? 0.5 : 0.25);
          EXPECT_NEAR(t.weight, tributary, 1e-14) << "D_jj = int N_j dA";
          EXPECT_NEAR(t.weight, nodes[i].area, 1e-14) << "D_jj = node area";
          total += t.weight;
          double sum = 0.;
          for (const double x : t.M)
            sum += x;
          EXPECT_NEAR(sum, t.weight, 1e-14) << "sum_m M_jm = D_jj";
          EXPECT_NEAR(t.weighted_gap, d * t.weight, 1e-15)
            << "weighted gap of a uniform gap d";
          EXPECT_NEAR(t.normal[0], 0., 1e-15);
          EXPECT_NEAR(t.normal[1], -1., 1e-15) << "outward slave normal";
          EXPECT_NEAR(t.normal[2], 0., 1e-15);
        }
      EXPECT_NEAR(total, 1., 1e-13) << "the D_jj sum to the slave's area";
    }
}

// R14.7: degree 2 in 3D is refused (the dual basis of quadratic
// quadrilaterals is not implemented), with a message that says so.
TEST(Mortar, RefusedForDegree2In3D)
{
  std::string text = stacked_blocks_3d(0., 1., 0., 1., 0., 2, 2, 2, "");
  text += "subsection Discretization\n  set Element degree = 2\nend\n";
  try
    {
      glide_test::ContactFixture<3> s(text, "mortar_refused_3d.prm");
      ADD_FAILURE() << "accepted: mortar of degree 2 in 3D";
    }
  catch (const std::exception &e)
    {
      EXPECT_NE(std::string(e.what()).find("mortar in 3D needs Element degree "
                                           "= 1"),
                std::string::npos)
        << e.what();
    }
}

// R16.1 with the pair memo of compute_3d() (Mortar::PairCache): the
// patches of a slave facet's four nodes share the integrals of its facet
// pairs, and an entry is used only at the coordinates it was computed
// with. So the terms and the linearization of every node are the same bit
// for bit whatever was evaluated before: in a fresh formulation in reverse
// order, and after an evaluation at another displacement. Curved master
// (distorted facets, the higher polygon rules), random state.
TEST(Mortar, PairMemoDoesNotChangeTheTerms3D)
{
  const std::string             text = ball_on_block_3d(false, false, "hard");
  glide_test::ContactFixture<3> s(text, "mortar_memo_3d.prm");
  glide_test::ContactFixture<3> fresh(text, "mortar_memo_3d_fresh.prm");
  VectorType                    U, v;
  glide_test::random_contact_state(s.e, s.contact, U, v, 7, 0.01, 0.02);
  VectorType other(U);
  other *= 1.5;
  const auto *m = dynamic_cast<const Mortar<3> *>(&s.contact.formulation_of(0));
  const auto *mf =
    dynamic_cast<const Mortar<3> *>(&fresh.contact.formulation_of(0));
  ASSERT_NE(m, nullptr);
  ASSERT_NE(mf, nullptr);
  const unsigned int n = s.contact.slave_nodes(0).size();

  using Linearization = typename Mortar<3>::Linearization;
  struct Result
  {
    Mortar<3>::Terms<double> terms;
    Linearization            l;
  };
  const auto evaluate =
    [&](const Mortar<3> &mortar, const VectorType &W, const bool reverse) {
      mortar.move(W);
      std::vector<Result> r(n);
      for (unsigned int k = 0; k < n; ++k)
        {
          const unsigned int i = reverse ? n - 1 - k : k;
          r[i].terms           = mortar.terms(i);
          const auto c         = mortar.evaluate(i, W);
          if (c.found())
            mortar.linearize(i, c, W, r[i].l);
        }
      return r;
    };
  const auto   first       = evaluate(*m, U, false);
  const auto   second      = evaluate(*m, other, false);
  const auto   again       = evaluate(*m, U, true);
  const auto   fresh_other = evaluate(*mf, other, true);
  const auto   fresh_U     = evaluate(*mf, U, false);
  unsigned int found       = 0;
  const auto   expect_same =
    [&](const Result &r, const Result &e, const unsigned int i) {
      EXPECT_EQ(r.terms.weight, e.terms.weight) << i;
      EXPECT_EQ(r.terms.weighted_gap, e.terms.weighted_gap) << i;
      EXPECT_EQ(r.terms.M, e.terms.M) << i;
      ASSERT_EQ(r.l.dofs, e.l.dofs) << i;
      EXPECT_EQ(r.l.gap, e.l.gap) << i;
      for (unsigned int a = 0; a < r.l.dgap.size(); ++a)
        EXPECT_EQ(r.l.dgap(a), e.l.dgap(a)) << i;
      for (unsigned int a = 0; a < r.l.dforce.m(); ++a)
        for (unsigned int b = 0; b < r.l.dforce.n(); ++b)
          EXPECT_EQ(r.l.dforce(a, b), e.l.dforce(a, b)) << i;
      found += e.l.dgap.size() > 0 ? 1 : 0;
    };
  for (unsigned int i = 0; i < n; ++i)
    {
      expect_same(again[i], first[i], i);
      expect_same(fresh_U[i], first[i], i);
      expect_same(second[i], fresh_other[i], i);
    }
  EXPECT_GT(found, 0u) << "some nodes have a constraint";
  // The two states differ (else the checks above prove nothing).
  EXPECT_NE(first[n / 2].terms.weighted_gap, second[n / 2].terms.weighted_gap);
}
