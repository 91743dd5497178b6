#include <glide/solver/load_stepper.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace glide
{
  namespace
  {
    /// The advice where the last attempt failed on an inverted element:
    /// at the smallest increment that is the mesh, not the step size (the
    /// message advised ever smaller steps; an outside trial's rigid circle
    /// pressed 0.98 of its radius into a neo-Hookean block).
    bool
    inverted(const std::string &reason)
    {
      return reason.find("inverted element") != std::string::npos;
    }
    constexpr const char *inverted_advice =
      "an element turned inside out at the smallest increment tried, so the "
      "mesh most likely cannot follow the deformation at this load: refine "
      "it where the bodies deform most, or end the loading before this load "
      "factor (smaller increments help only if the last converged step was "
      "far from it: 'Load stepping/Number of steps', 'Maximum cut-backs')";
  } // namespace

  LoadStepper::LoadStepper(const LoadSteppingParameters &parameters)
    : parameters(parameters)
    , nominal(1. / parameters.number_of_steps)
    , dt_min(nominal *
             std::pow(parameters.cut_back_factor, parameters.maximum_cut_backs))
    , dt(nominal)
  {}

  bool
  LoadStepper::running() const
  {
    return t < 1. - 1e-12;
  }

  double
  LoadStepper::begin_step()
  {
    t_new = std::min(1., t + dt);
    if (1. - t_new < 1e-3 * dt)
      t_new = 1.;
    return t_new;
  }

  void
  LoadStepper::accept()
  {
    t = t_new;
    ++n_steps;
    n_step_cut_backs = 0;
    // After a cut-back, grow the increment again towards the nominal one.
    dt = std::min(nominal, 2 * dt);
  }

  void
  LoadStepper::reject(const std::string &reason)
  {
    t_new                  = t;
    const std::string step = "load step " + std::to_string(n_steps + 1);
    if (n_step_cut_backs >= parameters.maximum_cut_backs)
      throw std::runtime_error(
        step + " failed after " + std::to_string(n_step_cut_backs) +
        " cut-backs (the log above says why each attempt failed; " +
        (inverted(reason) && n_step_cut_backs > 0 ?
           std::string(inverted_advice) :
           std::string(
             "if its residuals were still falling, raise 'Nonlinear "
             "solver/Maximum iterations', otherwise take smaller steps, "
             "'Load stepping/Number of steps', or allow more cut-backs, "
             "'Load stepping/Maximum cut-backs'")) +
        "): " + reason);
    // The floor, with a margin for the rounding of repeated halving.
    if (dt <= dt_min * (1. + 1e-9))
      {
        // The notes on what may have caused the failure ("\nNote: ...")
        // after the advice that belongs to the reason.
        const auto         notes = reason.find("\nNote: ");
        std::ostringstream text;
        text << step << " failed at load factor " << t
             << " with the smallest increment the scene allows (" << dt_min
             << " = 1 / 'Number of steps' x 'Cut-back factor' ^ 'Maximum "
                "cut-backs'): "
             << reason.substr(0, notes) << "; "
             << (inverted(reason) ?
                   inverted_advice :
                   "raise 'Load stepping/Maximum cut-backs' or 'Number of "
                   "steps' if smaller increments should be tried")
             << (notes == std::string::npos ? std::string() :
                                              reason.substr(notes));
        throw std::runtime_error(text.str());
      }
    ++n_cut_backs;
    ++n_step_cut_backs;
    dt = std::max(dt_min, dt * parameters.cut_back_factor);
  }
} // namespace glide
