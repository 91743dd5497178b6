#pragma once

#include <glide/solver/multiplier_condensation.h>
#include <glide/solver/solver_parameters.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

class Epetra_MultiVector;
class Epetra_LinearProblem;
class Epetra_CrsMatrix;
class Amesos_BaseSolver;

namespace glide
{
  /**
   * GMRES's stopping test, which also ends the solve (as a failure, with
   * stalled() set) once the residual has fallen by less than a tenth over
   * the last 200 iterations: restarted GMRES that stalls above its
   * tolerance (a nearly singular Jacobian) otherwise runs to the iteration
   * limit, up to 2000 iterations of no use. LinearSolver::solve() decides
   * what its last iterate is worth.
   */
  class StallingControl : public dealii::SolverControl
  {
  public:
    using dealii::SolverControl::SolverControl;

    State
    check(const unsigned int step, const double value) override;

    /// Whether the last solve ended by stalling.
    bool
    stalled() const
    {
      return has_stalled;
    }

    /// Iterations over which the residual must fall by a tenth.
    static constexpr unsigned int window = 200;

  private:
    bool                has_stalled = false;
    std::vector<double> history;
  };

  /**
   * The linear solver inside each Newton iteration (P3.3): a sparse direct
   * solver (Amesos MUMPS or KLU; both accept unsymmetric matrices and
   * distributed matrices), or GMRES with Trilinos ML algebraic multigrid
   * whose near null space is given by the caller (rigid-body modes).
   */
  class LinearSolver
  {
  public:
    LinearSolver(const LinearSolverParameters &parameters, MPI_Comm comm);
    ~LinearSolver();

    /// Decide between direct and AMG for a problem of @p n_dofs DoFs in
    /// @p dim dimensions; returns "direct" or "amg".
    std::string
    choose(const unsigned int                    dim,
           const dealii::types::global_dof_index n_dofs);

    /// Release the factorization or preconditioner, which refer to the
    /// matrix they were built from: call this before that matrix is
    /// re-initialized (a new sparsity pattern).
    void
    clear()
    {
      direct.reset();
      direct_problem.reset();
      factored = nullptr;
      amg.reset();
    }

    /// Solve hard-contact systems by eliminating their multipliers first
    /// (AMG only; see MultiplierCondensation).
    void
    set_condensation(std::unique_ptr<MultiplierCondensation> c)
    {
      condensation = std::move(c);
    }

    /// Closed contact multipliers eliminated at the last initialize() (0
    /// without condensation).
    unsigned int
    n_condensed() const
    {
      return condensation && kind == "amg" && fallback.empty() ?
               condensation->n_closed() :
               0;
    }

    /// False if solve() no longer reads the matrix given to initialize()
    /// (AMG on the condensed system): the caller may release it until the
    /// next initialize().
    bool
    keeps_matrix() const
    {
      return !(condensation && kind == "amg" && fallback.empty());
    }

    /// Why the last initialize() took the direct solver although AMG was
    /// chosen (the contact multipliers of that Jacobian could not be
    /// eliminated: MultiplierCondensation::NotCondensable); empty if it
    /// did not.
    const std::string &
    fallback_reason() const
    {
      return fallback;
    }

    /// Factorize (direct) or build the AMG hierarchy for @p matrix.
    void
    /// With AMG on the condensed system, @p release is called once the
    /// multipliers are eliminated and before the hierarchy is built: the
    /// caller may free @p matrix there (keeps_matrix() is false), which
    /// takes it off the run's peak memory.
    initialize(
      const dealii::TrilinosWrappers::SparseMatrix             &matrix,
      const std::vector<dealii::TrilinosWrappers::MPI::Vector> &near_null_space,
      const std::function<void()>                              &release = {});

    /// Solve matrix * x = b to @p relative_tolerance (ignored by the direct
    /// solver); returns the number of Krylov iterations (1 for direct).
    /// Throws std::runtime_error if the solver fails (for GMRES: stops at
    /// its iteration limit above inexact_limit).
    unsigned int
    solve(const dealii::TrilinosWrappers::MPI::Vector &b,
          dealii::TrilinosWrappers::MPI::Vector       &x,
          const double                                 relative_tolerance);

    /// "direct (MUMPS)", "AMG-GMRES", ... for the log.
    std::string
    description() const;

    /// GMRES that stalls (the residual falls by less than a tenth over 200
    /// iterations) or reaches its iteration limit after it has reduced the
    /// residual to this fraction of its start: solve() then returns its
    /// last iterate as an inexact Newton step instead of failing.
    static constexpr double inexact_limit = 1e-3;

    /// The residual reduction of the last solve() if it was such an inexact
    /// step, 0 otherwise.
    double
    last_inexact_reduction() const
    {
      return last_inexact;
    }

    /// Whether that inexact solve stalled (rather than reaching the
    /// iteration limit).
    bool
    last_inexact_stalled() const
    {
      return last_stalled;
    }

  private:
    const LinearSolverParameters                  parameters;
    MPI_Comm                                      comm;
    std::string                                   kind;
    const dealii::TrilinosWrappers::SparseMatrix *matrix = nullptr;
    /// The direct solver (Amesos) and its linear problem. Its symbolic
    /// factorization (ordering and analysis) depends on the sparsity
    /// pattern only: it is kept while the matrix stays the same object
    /// with the same pattern (the Newton iterations between two clear()),
    /// and only the numeric factorization is redone.
    std::unique_ptr<Epetra_LinearProblem> direct_problem;
    std::unique_ptr<Amesos_BaseSolver>    direct;
    const Epetra_CrsMatrix               *factored         = nullptr;
    long long                             factored_entries = -1;
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
    std::unique_ptr<Epetra_MultiVector>                        null_space;
    std::unique_ptr<MultiplierCondensation>                    condensation;
    double last_inexact = 0.;
    bool   last_stalled = false;
    /// See fallback_reason().
    std::string fallback;

    /// Factorize @p A with the direct solver.
    void
    factorize(const dealii::TrilinosWrappers::SparseMatrix &A);
  };
} // namespace glide
