// Unit tests of GMRES's stopping test (P3.3, StallingControl). Why the
// expected answers are right: a residual that falls by 1 % per iteration
// falls by far more than a tenth over any 200 iterations (0.99^200 = 0.13),
// so the test keeps iterating; a residual that stays flat (or falls by
// 0.01 % per iteration, 0.9999^200 = 0.98) has not fallen by a tenth once
// 200 iterations have passed, so the test fails there, not before; a
// residual below the tolerance succeeds whatever its history.
#include <glide/solver/linear_solver.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace dealii;
using namespace glide;

TEST(StallingControl, IteratesWhileTheResidualFalls)
{
  StallingControl control(2000, 1e-30);
  for (unsigned int step = 0; step <= 1000; ++step)
    ASSERT_EQ(control.check(step, std::pow(0.99, step)), SolverControl::iterate)
      << "step " << step;
  EXPECT_FALSE(control.stalled());
}

TEST(StallingControl, FailsOnceTheResidualStalledForTheWindow)
{
  for (const double rate : {1., 0.9999})
    {
      StallingControl control(2000, 1e-30);
      unsigned int    step = 0;
      for (; step < 2000; ++step)
        if (control.check(step, std::pow(rate, step)) != SolverControl::iterate)
          break;
      EXPECT_EQ(step, StallingControl::window) << "rate " << rate;
      EXPECT_EQ(control.last_check(), SolverControl::failure);
      EXPECT_TRUE(control.stalled());
    }
}

TEST(StallingControl, SucceedsBelowTheToleranceAndStopsAtTheLimit)
{
  StallingControl converged(2000, 1e-3);
  EXPECT_EQ(converged.check(0, 1.), SolverControl::iterate);
  EXPECT_EQ(converged.check(1, 1e-4), SolverControl::success);
  EXPECT_FALSE(converged.stalled());

  // The iteration limit is SolverControl's own failure, not a stall.
  StallingControl limited(50, 1e-30);
  unsigned int    step = 0;
  while (limited.check(step, std::pow(0.5, step)) == SolverControl::iterate)
    ++step;
  EXPECT_EQ(step, 50u);
  EXPECT_EQ(limited.last_check(), SolverControl::failure);
  EXPECT_FALSE(limited.stalled());
}
