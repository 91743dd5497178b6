#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace glide
{
  /// Settings of the KINSOL-driven Newton iteration of each load step.
  struct NonlinearSolverParameters
  {
    /// "newton" (full steps), "line search", or "automatic" (newton with
    /// contact, line search without).
    std::string strategy = "automatic";
    /// Retry a failed step with line search before cutting back (set by
    /// 'automatic' in scenes with contact).
    bool retry_with_line_search = false;
    /// Stop when the scaled max-norm of the residual is below this. The
    /// residual is scaled by 1 / (E_min * A_ref), A_ref the mean boundary
    /// facet measure, so the tolerance is unit-free (a strain-like number).
    double tolerance = 1e-10;
    /// The scaled residual that round-off alone can leave (set by the
    /// problem from its bodies, Elasticity::round_off_floor(), not read
    /// from the scene): a solve that stops above the tolerance but at or
    /// below this counts as converged, and says so (Result::at_floor).
    double round_off_floor = 0.;
    /// KINSOL's scaled step tolerance (set by the problem, not read).
    double step_tolerance = 1e-14;
    /// A linear problem (no contact, geometrically linear; set by the
    /// problem, not read): its first Newton step is the solution, so KINSOL
    /// takes it whatever its length. Otherwise KINSOL's default bound on a
    /// step (1000 in its scaled 2-norm, or 1000 ||D_u u_0||) stands, which
    /// shortens the wild first steps of a body held only by contact.
    bool         linear_problem     = false;
    unsigned int maximum_iterations = 25;
    /// Jacobian re-use: 1 assembles the Jacobian every iteration.
    unsigned int maximum_setup_calls = 1;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm);
  };

  /// Settings of the linear solver used inside each Newton iteration.
  struct LinearSolverParameters
  {
    /// "automatic", "direct" or "amg".
    std::string type = "automatic";
    /// Amesos solver for "direct": "MUMPS" or "KLU".
    std::string direct_solver = "MUMPS";
    /// Largest number of DoFs for which "automatic" picks the direct solver
    /// in 3D (2D problems always get the direct solver).
    unsigned int automatic_direct_limit = 200000;
    double       relative_tolerance     = 1e-8;
    unsigned int maximum_iterations     = 2000;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm);
  };

  /// Load stepping: the load factor t runs from 0 to 1 in equal steps;
  /// failed steps are cut back and retried.
  struct LoadSteppingParameters
  {
    unsigned int number_of_steps   = 1;
    unsigned int maximum_cut_backs = 6;
    double       cut_back_factor   = 0.5;
    bool         tangent_predictor = true;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm);
  };
} // namespace glide
