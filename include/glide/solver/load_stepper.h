#pragma once

#include <glide/solver/solver_parameters.h>

#include <string>

namespace glide
{
  /**
   * The load factor t of a run, from 0 to 1 (P3.3): nominal increments
   * 1 / 'Number of steps'; a failed step is cut back by 'Cut-back factor'
   * and retried, at most 'Maximum cut-backs' times in a row; after a
   * converged step the increment grows again by a factor 2 towards the
   * nominal one.
   *
   * The increment never falls below the smallest one the parameters allow
   * within one step, nominal x factor^(maximum cut-backs): successive steps
   * that converge only after cut-backs could otherwise shrink it without
   * bound (a faceted ironing run went down to increments of 1e-16, where t
   * + dt rounds to t, and "converged" steps of zero increment alternated
   * with failures forever). A step that fails at that floor ends the run.
   */
  class LoadStepper
  {
  public:
    explicit LoadStepper(const LoadSteppingParameters &parameters);

    /// True while t < 1.
    bool
    running() const;

    /// Begin the next step: the load factor to solve for.
    double
    begin_step();

    /// The step converged: t moves on to the step's load factor.
    void
    accept();

    /// The step failed with @p reason: cut back (t stays), or throw a
    /// std::runtime_error naming the step and the reason if the step was
    /// cut back 'Maximum cut-backs' times or its increment is at the floor.
    void
    reject(const std::string &reason);

    /// Load factor of the last converged step.
    double
    time() const
    {
      return t;
    }

    /// Load factor of the step begun last.
    double
    target() const
    {
      return t_new;
    }

    /// Current increment.
    double
    increment() const
    {
      return dt;
    }

    /// The smallest increment.
    double
    minimum_increment() const
    {
      return dt_min;
    }

    /// Converged steps so far.
    unsigned int
    steps() const
    {
      return n_steps;
    }

    /// Cut-backs of the whole run, and of the current step.
    unsigned int
    cut_backs() const
    {
      return n_cut_backs;
    }
    unsigned int
    step_cut_backs() const
    {
      return n_step_cut_backs;
    }

  private:
    const LoadSteppingParameters parameters;
    const double                 nominal;
    const double                 dt_min;
    double                       t     = 0.;
    double                       t_new = 0.;
    double                       dt;
    unsigned int n_steps = 0, n_cut_backs = 0, n_step_cut_backs = 0;
  };
} // namespace glide
