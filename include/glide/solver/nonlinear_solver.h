#pragma once

#include <glide/solver/solver_parameters.h>

#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <string>

namespace glide
{
  /**
   * The only code that talks to SUNDIALS (P3.1): solves F(U) = 0 with
   * KINSOL through deal.II's SUNDIALS::KINSOL wrapper, with the Jacobian
   * supplied by the caller. It knows nothing about mechanics or contact:
   * the caller gives callbacks and scalings.
   *
   * deal.II 9.4.1 checks KINSOL's return status only in debug builds, so
   * after every solve the residual is evaluated again here and the result
   * says whether the scaled max-norm is really below the tolerance.
   */
  class NonlinearSolver
  {
  public:
    using VectorType = dealii::TrilinosWrappers::MPI::Vector;

    /// What the caller provides.
    struct Callbacks
    {
      /// A vector with the layout of U (locally owned, not ghosted).
      std::function<void(VectorType &)> reinit_vector;
      /// F(U); may throw std::runtime_error for a recoverable failure
      /// (e.g. an inverted element), which fails the solve with its message.
      std::function<void(const VectorType &U, VectorType &F)> residual;
      /// Assemble and factorize the Jacobian at U.
      std::function<void(const VectorType &U)> setup_jacobian;
      /// Solve J dx = rhs; returns linear iterations.
      std::function<unsigned int(const VectorType &rhs, VectorType &dx)>
        solve_jacobian;
      /// Called once per Newton iteration with its number and scaled
      /// residual norm (for the log).
      std::function<void(unsigned int, double)> report;
    };

    struct Result
    {
      bool         converged         = false;
      unsigned int iterations        = 0;
      unsigned int linear_iterations = 0;
      double       residual_norm     = 0.; ///< scaled max-norm at the end
      /// Converged above the tolerance, at the round-off floor
      /// (NonlinearSolverParameters::round_off_floor).
      bool        at_floor = false;
      std::string message; ///< why it failed
    };

    NonlinearSolver(const NonlinearSolverParameters &parameters, MPI_Comm comm);

    /**
     * Solve from the initial guess @p U. Residual rows are multiplied entry
     * by entry by @p residual_scale and unknowns by @p solution_scale inside
     * KINSOL so that its tolerances are unit-free.
     */
    Result
    solve(VectorType       &U,
          const Callbacks  &callbacks,
          const VectorType &residual_scale,
          const VectorType &solution_scale);

    /// Convenience: one scale for every row and one for every unknown.
    Result
    solve(VectorType      &U,
          const Callbacks &callbacks,
          const double     residual_scale,
          const double     solution_scale);

  private:
    const NonlinearSolverParameters parameters;
    MPI_Comm                        comm;
  };
} // namespace glide
