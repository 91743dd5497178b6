// Unit tests of the KINSOL driver (P3.1). Why the expected answers are
// right: F_i(x) = x_i^3 + x_i - b_i has one real root per component, and
// Newton converges to it quadratically, so a handful of iterations suffice;
// F_i(x) = x_i^2 + 1 has no real root, so the solve must report failure
// even in a release build of deal.II, where KINSOL's status is not checked
// (the driver re-evaluates the residual itself).
#include <glide/solver/nonlinear_solver.h>

#include <deal.II/base/index_set.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace dealii;
using namespace glide;

namespace
{
  struct Problem
  {
    IndexSet                    owned{8};
    NonlinearSolver::VectorType diagonal;
    bool                        solvable = true;
    unsigned int                reports  = 0;

    Problem()
    {
      owned.add_range(0, 8);
    }

    NonlinearSolver::Callbacks
    callbacks()
    {
      NonlinearSolver::Callbacks cb;
      cb.reinit_vector = [this](NonlinearSolver::VectorType &v) {
        v.reinit(owned, MPI_COMM_WORLD);
      };
      cb.residual = [this](const NonlinearSolver::VectorType &x,
                           NonlinearSolver::VectorType       &F) {
        for (unsigned int i = 0; i < 8; ++i)
          F[i] =
            solvable ? x[i] * x[i] * x[i] + x[i] - (1. + i) : x[i] * x[i] + 1.;
        F.compress(VectorOperation::insert);
      };
      cb.setup_jacobian = [this](const NonlinearSolver::VectorType &x) {
        diagonal.reinit(owned, MPI_COMM_WORLD);
        for (unsigned int i = 0; i < 8; ++i)
          diagonal[i] = solvable ? 3 * x[i] * x[i] + 1. :
                                   2 * x[i] + (x[i] == 0 ? 1e-3 : 0.);
        diagonal.compress(VectorOperation::insert);
      };
      cb.solve_jacobian = [this](const NonlinearSolver::VectorType &rhs,
                                 NonlinearSolver::VectorType       &dx) {
        for (unsigned int i = 0; i < 8; ++i)
          dx[i] = rhs[i] / diagonal[i];
        dx.compress(VectorOperation::insert);
        return 1u;
      };
      cb.report = [this](unsigned int, double) { ++reports; };
      return cb;
    }
  };
} // namespace

TEST(NonlinearSolver, ConvergesQuadraticallyOnASolvableSystem)
{
  Problem                   p;
  NonlinearSolverParameters parameters;
  parameters.tolerance = 1e-12;
  NonlinearSolver             solver(parameters, MPI_COMM_WORLD);
  NonlinearSolver::VectorType x(p.owned, MPI_COMM_WORLD);
  const auto                  result = solver.solve(x, p.callbacks(), 1., 1.);
  EXPECT_TRUE(result.converged) << result.message;
  EXPECT_LE(result.iterations, 10u);
  EXPECT_GE(result.iterations, 3u);
  EXPECT_LE(result.residual_norm, 1e-12);
  for (unsigned int i = 0; i < 8; ++i)
    EXPECT_NEAR(x[i] * x[i] * x[i] + x[i], 1. + i, 1e-10);
  EXPECT_EQ(p.reports, result.iterations);
}

TEST(NonlinearSolver, ReportsFailureWhenThereIsNoSolution)
{
  Problem p;
  p.solvable = false;
  NonlinearSolverParameters parameters;
  parameters.maximum_iterations = 8;
  NonlinearSolver             solver(parameters, MPI_COMM_WORLD);
  NonlinearSolver::VectorType x(p.owned, MPI_COMM_WORLD);
  x                 = 0.5;
  const auto result = solver.solve(x, p.callbacks(), 1., 1.);
  EXPECT_FALSE(result.converged);
  EXPECT_FALSE(result.message.empty());
  EXPECT_GT(result.residual_norm, 0.5);
  // The initial guess is restored after a failure.
  EXPECT_EQ(x[0], 0.5);
}

TEST(NonlinearSolver, ResidualScalingMakesToleranceUnitFree)
{
  // The same system with residuals in other units (x 1e6) and the matching
  // scaling needs the same number of iterations.
  unsigned int iterations[2];
  for (unsigned int k = 0; k < 2; ++k)
    {
      Problem      p;
      const double units = k == 0 ? 1. : 1e6;
      auto         cb    = p.callbacks();
      auto         plain = cb.residual;
      cb.residual        = [&](const NonlinearSolver::VectorType &x,
                        NonlinearSolver::VectorType       &F) {
        plain(x, F);
        F *= units;
      };
      auto plain_solve  = cb.solve_jacobian;
      cb.solve_jacobian = [&](const NonlinearSolver::VectorType &rhs,
                              NonlinearSolver::VectorType       &dx) {
        NonlinearSolver::VectorType r = rhs;
        r /= units;
        return plain_solve(r, dx);
      };
      NonlinearSolverParameters   parameters;
      NonlinearSolver             solver(parameters, MPI_COMM_WORLD);
      NonlinearSolver::VectorType x(p.owned, MPI_COMM_WORLD);
      const auto                  result = solver.solve(x, cb, 1. / units, 1.);
      ASSERT_TRUE(result.converged) << result.message;
      iterations[k] = result.iterations;
    }
  EXPECT_EQ(iterations[0], iterations[1]);
}

// A residual with noise of 1e-8 (a fixed function of x, as round-off in an
// assembly is) cannot be reduced below about 1e-8: with a tolerance of
// 1e-12 the solve fails, unless the round-off floor says that 1e-7 is as
// far as the arithmetic goes; then it converges, flagged at_floor, with the
// solution correct to the noise. A clean residual never gets the flag.
TEST(NonlinearSolver, AcceptsAStallAtTheRoundOffFloorOnly)
{
  for (const double floor : {0., 1e-7})
    for (const bool noisy : {true, false})
      {
        Problem p;
        auto    cb    = p.callbacks();
        auto    plain = cb.residual;
        cb.residual   = [&](const NonlinearSolver::VectorType &x,
                          NonlinearSolver::VectorType       &F) {
          plain(x, F);
          if (noisy)
            for (unsigned int i = 0; i < 8; ++i)
              F[i] += 1e-8 * std::sin(1e9 * x[i] + i);
          F.compress(VectorOperation::insert);
        };
        NonlinearSolverParameters parameters;
        parameters.tolerance       = 1e-12;
        parameters.round_off_floor = floor;
        parameters.strategy        = "line search";
        NonlinearSolver             solver(parameters, MPI_COMM_WORLD);
        NonlinearSolver::VectorType x(p.owned, MPI_COMM_WORLD);
        const auto                  result = solver.solve(x, cb, 1., 1.);
        const std::string what = std::string(noisy ? "noisy" : "clean") +
                                 ", floor " + std::to_string(floor);
        EXPECT_EQ(result.converged, !noisy || floor > 0.) << what;
        EXPECT_EQ(result.at_floor, noisy && floor > 0.) << what;
        if (result.converged)
          {
            for (unsigned int i = 0; i < 8; ++i)
              EXPECT_NEAR(x[i] * x[i] * x[i] + x[i], 1. + i, 1e-7) << what;
          }
      }
}

// KINSOL prints its failures to stderr ("[KINSOL ERROR]  KINSol / The line
// search algorithm was unable to ..."), also for attempts that glide then
// retries successfully. The driver keeps them off the terminal and puts
// KINSOL's reason into the failure message instead; anything else written
// to stderr during the solve (another library's warning) still gets
// there.
TEST(NonlinearSolver, KinsolsFailureIsInTheMessageNotOnStderr)
{
  Problem p;
  auto    cb    = p.callbacks();
  auto    plain = cb.residual;
  bool    said  = false;
  cb.residual   = [&](const NonlinearSolver::VectorType &x,
                    NonlinearSolver::VectorType       &F) {
    plain(x, F);
    for (unsigned int i = 0; i < 8; ++i)
      F[i] += 1e-8 * std::sin(1e9 * x[i] + i);
    F.compress(VectorOperation::insert);
    if (!said)
      std::fprintf(stderr, "a library's warning\n");
    said = true;
  };
  NonlinearSolverParameters parameters;
  parameters.tolerance = 1e-12;
  parameters.strategy  = "line search";
  NonlinearSolver             solver(parameters, MPI_COMM_WORLD);
  NonlinearSolver::VectorType x(p.owned, MPI_COMM_WORLD);
  testing::internal::CaptureStderr();
  const auto        result = solver.solve(x, cb, 1., 1.);
  const std::string err    = testing::internal::GetCapturedStderr();
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(err, "a library's warning\n");
  EXPECT_NE(result.message.find("The line search algorithm was unable to "
                                "find an iterate sufficiently distinct"),
            std::string::npos)
    << result.message;
}
