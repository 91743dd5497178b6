// Unit tests of the elasticity residual and Jacobian (P1.1, P1.2). Why the
// expected answers are right: the Jacobian must be the derivative of the
// residual, so J v must match central finite differences of F along any
// direction v that respects the constraints, for the nonlinear
// (neo-Hookean) law in plane strain, axisymmetric (with the hoop term) and
// 3D analyses, on a mesh with hanging nodes, degree 1 and 2.
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
  std::string
  scene_text(const std::string &analysis, const unsigned int degree)
  {
    const bool         three = analysis == "3d";
    std::ostringstream s;
    s << "set Dimension = " << (three ? 3 : 2)
      << "\nset Analysis type = " << analysis << "\n"
      << "set Boundary conditions = hold, load\n"
      << "subsection Discretization\n  set Element degree = " << degree
      << "\n  set Geometric nonlinearity = true\nend\n"
      << "subsection Body body\n  subsection Block\n    set Lower corner = "
      << (three ? "0, 0, 0" : "0.2, 0")
      << "\n    set Upper corner = " << (three ? "1, 1, 1" : "1.2, 1")
      << "\n    set Subdivisions = " << (three ? "2, 1, 1" : "2, 2")
      << "\n  end\n"
      << "  subsection Refinement\n    set Local refinements = 1\n    set Refinement radius = 0.3\n"
      << "    set Refinement point = " << (three ? "0, 0, 0" : "0.2, 0")
      << "\n  end\nend\n"
      << "subsection Boundary condition hold\n  set Surface = body.bottom\n  set Type = fixed\nend\n"
      << "subsection Boundary condition load\n  set Surface = body.top\n  set Type = pressure\n"
      << "  set Function = 0.1*t\nend\n";
    return s.str();
  }

  template <int dim>
  void
  check_jacobian(const std::string &analysis, const unsigned int degree)
  {
    const Scene scene =
      Scene::read(glide_test::write_file("jacobian_" + analysis + ".prm",
                                         scene_text(analysis, degree)));
    TimerOutput     timer(MPI_COMM_WORLD,
                      std::cout,
                      TimerOutput::never,
                      TimerOutput::wall_times);
    Elasticity<dim> e(scene, MPI_COMM_WORLD, timer);
    e.setup();
    e.setup_system();
    // There are hanging nodes (local refinement), so the test also covers
    // the condensation of the residual and the Jacobian.
    ASSERT_GT(e.update_constraints().n_constraints(), 0u);

    std::mt19937                           gen(42);
    std::uniform_real_distribution<double> dist(-0.005, 0.005);
    VectorType U(e.locally_owned(), MPI_COMM_WORLD), v(U);
    for (const auto i : e.locally_owned())
      {
        U[i] = dist(gen);
        v[i] = dist(gen);
      }
    U.compress(VectorOperation::insert);
    v.compress(VectorOperation::insert);
    e.constraints_at(1.).distribute(U);
    e.update_constraints().distribute(v);

    MatrixType J;
    J.reinit(e.matrix_pattern());
    e.jacobian(U, J);
    VectorType Jv(U), Fp(U), Fm(U), Up(U), Um(U);
    J.vmult(Jv, v);
    const double h = 1e-6;
    Up.add(h, v);
    Um.add(-h, v);
    e.residual(Up, 1., Fp);
    e.residual(Um, 1., Fm);
    Fp -= Fm;
    Fp /= 2 * h;
    // Compare only unconstrained rows (constrained rows hold a diagonal
    // scaling entry in J, zero in F).
    double err = 0, ref = 0;
    for (const auto i : e.locally_owned())
      if (!e.update_constraints().is_constrained(i))
        {
          err = std::max(err, std::abs(Jv[i] - Fp[i]));
          ref = std::max(ref, std::abs(Fp[i]));
        }
    EXPECT_GT(ref, 0.);
    EXPECT_LT(err, 1e-6 * ref) << analysis << " Q" << degree;
  }
} // namespace

TEST(Elasticity, JacobianMatchesFiniteDifferencesPlaneStrain)
{
  check_jacobian<2>("plane strain", 1);
  check_jacobian<2>("plane strain", 2);
}

TEST(Elasticity, JacobianMatchesFiniteDifferencesAxisymmetric)
{
  check_jacobian<2>("axisymmetric", 1);
  check_jacobian<2>("axisymmetric", 2);
}

TEST(Elasticity, JacobianMatchesFiniteDifferences3D)
{
  check_jacobian<3>("3d", 1);
}

TEST(Elasticity, UnknownSurfaceIsAnInputError)
{
  std::string text = scene_text("plane strain", 1);
  text.replace(text.find("body.top"), 8, "body.lid");
  const Scene scene =
    Scene::read(glide_test::write_file("unknown_surface.prm", text));
  TimerOutput   timer(MPI_COMM_WORLD,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  Elasticity<2> e(scene, MPI_COMM_WORLD, timer);
  try
    {
      e.setup();
      FAIL() << "no error";
    }
  catch (const InputError &err)
    {
      const std::string m = err.what();
      EXPECT_NE(m.find("Boundary condition load/Surface"), std::string::npos)
        << m;
      EXPECT_NE(m.find("body.lid"), std::string::npos) << m;
      EXPECT_NE(m.find("body.top"), std::string::npos)
        << "lists known surfaces: " << m;
    }
}

TEST(Elasticity, BadExpressionIsAnInputError)
{
  std::string text = scene_text("plane strain", 1);
  text.replace(text.find("0.1*t"), 5, "0.1*tt");
  const Scene scene =
    Scene::read(glide_test::write_file("bad_expression.prm", text));
  TimerOutput   timer(MPI_COMM_WORLD,
                    std::cout,
                    TimerOutput::never,
                    TimerOutput::wall_times);
  Elasticity<2> e(scene, MPI_COMM_WORLD, timer);
  EXPECT_THROW(e.setup(), InputError);
}
