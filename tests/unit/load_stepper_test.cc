// The load stepper (P3.3): nominal increments, cut-backs, growth after a
// cut-back, and a floor on the increment so that a run cannot go on
// forever with vanishing increments.
#include <glide/solver/load_stepper.h>

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

using namespace glide;

namespace
{
  LoadSteppingParameters
  parameters(const unsigned int steps,
             const unsigned int cut_backs,
             const double       factor)
  {
    LoadSteppingParameters p;
    p.number_of_steps   = steps;
    p.maximum_cut_backs = cut_backs;
    p.cut_back_factor   = factor;
    return p;
  }
} // namespace

TEST(LoadStepper, NominalStepsEndExactlyAtOne)
{
  LoadStepper  stepper(parameters(3, 4, 0.5));
  unsigned int n = 0;
  while (stepper.running())
    {
      const double t = stepper.begin_step();
      EXPECT_NEAR(t, (n + 1) / 3., 1e-15);
      stepper.accept();
      ++n;
    }
  EXPECT_EQ(n, 3u);
  EXPECT_EQ(stepper.time(), 1.);
  EXPECT_EQ(stepper.steps(), 3u);
}

TEST(LoadStepper, CutBackThenGrowBackToNominal)
{
  LoadStepper stepper(parameters(4, 4, 0.5));
  EXPECT_DOUBLE_EQ(stepper.begin_step(), 0.25);
  stepper.reject("test");
  EXPECT_EQ(stepper.time(), 0.);
  EXPECT_DOUBLE_EQ(stepper.begin_step(), 0.125);
  stepper.accept();
  EXPECT_DOUBLE_EQ(stepper.begin_step(), 0.375); // grown back to 0.25
  stepper.accept();
  EXPECT_EQ(stepper.cut_backs(), 1u);
  EXPECT_EQ(stepper.step_cut_backs(), 0u);
}

TEST(LoadStepper, TooManyCutBacksInOneStepEndTheRun)
{
  LoadStepper stepper(parameters(1, 2, 0.5));
  stepper.begin_step();
  stepper.reject("a");
  stepper.begin_step();
  stepper.reject("b");
  stepper.begin_step();
  try
    {
      stepper.reject("no convergence");
      FAIL() << "no exception";
    }
  catch (const std::runtime_error &e)
    {
      // The reason, then what to change (until 2026-12-06 no advice).
      EXPECT_EQ(std::string(e.what()),
                "load step 1 failed after 2 cut-backs (the log above says "
                "why each attempt failed; if its residuals were still "
                "falling, raise 'Nonlinear solver/Maximum iterations', "
                "otherwise take smaller steps, 'Load stepping/Number of "
                "steps', or allow more cut-backs, 'Load stepping/Maximum "
                "cut-backs'): no convergence");
    }
}

TEST(LoadStepper, IncrementNeverFallsBelowTheFloor)
{
  // Steps that converge only after cut-backs, one after another: before
  // the floor, the increment halved without bound (a faceted ironing run
  // reached 1e-16, where t + dt == t, and ran forever). Now it stays at
  // or above nominal x factor^maximum cut-backs, and a failure there ends
  // the run with a message that names the floor.
  LoadStepper  stepper(parameters(10, 3, 0.5));
  const double floor = 0.1 * 0.125;
  EXPECT_DOUBLE_EQ(stepper.minimum_increment(), floor);
  bool ended = false;
  for (unsigned int k = 0; k < 1000 && !ended; ++k)
    {
      const double t = stepper.begin_step();
      EXPECT_GT(t, stepper.time());
      EXPECT_GE(stepper.increment(), floor * (1. - 1e-12));
      try
        {
          // Fail twice, then converge: the increment shrinks by 4 per
          // converged step and grows by 2.
          stepper.reject("x");
          stepper.begin_step();
          stepper.reject("y");
          stepper.begin_step();
          stepper.accept();
        }
      catch (const std::runtime_error &e)
        {
          ended = true;
          EXPECT_NE(std::string(e.what()).find("smallest increment"),
                    std::string::npos)
            << e.what();
          EXPECT_NE(std::string(e.what()).find("Maximum cut-backs"),
                    std::string::npos)
            << e.what();
        }
    }
  EXPECT_TRUE(ended) << "the run ends instead of going on forever";
  EXPECT_LT(stepper.time(), 1.);
}

// A step whose last attempt inverts an element at the smallest increment:
// the message says the mesh cannot follow, not only "smaller steps" (an
// outside trial's deep indentation; until 2026-12-07 it advised more
// cut-backs only). Other reasons keep the step-size advice.
TEST(LoadStepper, InvertedElementAtTheFloorBlamesTheMesh)
{
  const std::string inverted = "inverted element (det F = -0.8 <= 0) in the "
                               "neo-Hookean material: the load step is too "
                               "large, or the mesh cannot follow the "
                               "deformation there";
  for (const unsigned int cut_backs : {0u, 2u})
    for (const bool by_inversion : {true, false})
      {
        LoadStepper stepper(parameters(1, cut_backs, 0.5));
        std::string message;
        try
          {
            for (unsigned int i = 0; i <= cut_backs; ++i)
              {
                stepper.begin_step();
                stepper.reject(by_inversion ? inverted : "stalled");
              }
          }
        catch (const std::runtime_error &e)
          {
            message = e.what();
          }
        // Without a cut-back (Maximum cut-backs = 0) only the nominal
        // step was tried: the step-size advice.
        EXPECT_EQ(message.find("the mesh most likely cannot follow the "
                               "deformation at this load") != std::string::npos,
                  by_inversion && cut_backs > 0)
          << message;
        EXPECT_NE(message.find(by_inversion ? "inverted element" : "stalled"),
                  std::string::npos)
          << message;
      }
  // At the floor of the increment (steps that converge only after two
  // cut-backs, as in IncrementNeverFallsBelowTheFloor).
  LoadStepper stepper(parameters(10, 3, 0.5));
  std::string message;
  for (unsigned int k = 0; k < 1000 && message.empty(); ++k)
    try
      {
        stepper.begin_step();
        stepper.reject(inverted);
        stepper.begin_step();
        stepper.reject(inverted);
        stepper.begin_step();
        stepper.accept();
      }
    catch (const std::runtime_error &e)
      {
        message = e.what();
      }
  EXPECT_NE(message.find("smallest increment"), std::string::npos) << message;
  EXPECT_NE(message.find("the mesh most likely cannot follow"),
            std::string::npos)
    << message;
}
