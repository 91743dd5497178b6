#include <glide/solver/linear_solver.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_gmres.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <iomanip>
#include <new>
#include <sstream>
#include <vector>

namespace glide
{
  using namespace dealii;

  SolverControl::State
  StallingControl::check(const unsigned int step, const double value)
  {
    const State state = SolverControl::check(step, value);
    if (state != iterate)
      return state;
    if (history.size() <= step)
      history.resize(step + 1, value);
    history[step] = value;
    if (step >= window && value > 0.9 * history[step - window])
      {
        has_stalled = true;
        lcheck      = failure;
        return failure;
      }
    return state;
  }

  LinearSolver::LinearSolver(const LinearSolverParameters &parameters,
                             MPI_Comm                      comm)
    : parameters(parameters)
    , comm(comm)
    , kind(parameters.type)
  {}

  LinearSolver::~LinearSolver() = default;

  std::string
  LinearSolver::choose(const unsigned int            dim,
                       const types::global_dof_index n_dofs)
  {
    if (parameters.type == "automatic")
      kind = (dim == 2 || n_dofs <= parameters.automatic_direct_limit) ?
               "direct" :
               "amg";
    else
      kind = parameters.type;
    return kind;
  }

  std::string
  LinearSolver::description() const
  {
    if (kind == "direct")
      return "direct (Amesos " + parameters.direct_solver + ")";
    return condensation ? "GMRES with ML algebraic multigrid (contact "
                          "multipliers eliminated)" :
                          "GMRES with ML algebraic multigrid";
  }

  namespace
  {
    /// The condensed matrix as the operator of deal.II's GMRES.
    struct EpetraOperator
    {
      const Epetra_CrsMatrix &matrix;

      void
      vmult(TrilinosWrappers::MPI::Vector       &dst,
            const TrilinosWrappers::MPI::Vector &src) const
      {
        const int ierr =
          matrix.Multiply(false, src.trilinos_vector(), dst.trilinos_vector());
        if (ierr != 0)
          throw std::runtime_error("Epetra_CrsMatrix::Multiply failed");
      }
    };
  } // namespace

  namespace
  {
    /// Amesos reports failures by status (a singular matrix: a non-zero
    /// status of the numeric factorization); KINSOL needs an exception.
    void
    check_amesos(const int status, const char *phase, Amesos_BaseSolver *solver)
    {
      if (status == 0)
        return;
      // MUMPS could not allocate its workspace (INFOG(1) = -13, global, so
      // every process sees it): out of memory, which no smaller load step
      // mends (main() says so and exits).
      if (auto *mumps = dynamic_cast<Amesos_Mumps *>(solver))
        if (mumps->GetINFOG() && mumps->GetINFOG()[0] == -13)
          throw std::bad_alloc();
      throw std::runtime_error(std::string("the direct solver's ") + phase +
                               " phase failed (status " +
                               std::to_string(status) + ")");
    }
  } // namespace

  void
  LinearSolver::factorize(const TrilinosWrappers::SparseMatrix &A)
  {
    const Epetra_CrsMatrix &M = A.trilinos_matrix();
    // A new matrix object or pattern (a caller that re-initializes the
    // matrix calls clear() first; the checks are a second guard):
    // ordering and symbolic analysis anew.
    if (!direct || factored != &M ||
        factored_entries != static_cast<long long>(M.NumGlobalNonzeros64()))
      {
        direct.reset();
        direct_problem = std::make_unique<Epetra_LinearProblem>();
        direct_problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&M));
        Amesos            factory;
        const std::string name =
          parameters.direct_solver == "MUMPS" ? "Amesos_Mumps" : "Amesos_Klu";
        direct.reset(factory.Create(name.c_str(), *direct_problem));
        if (!direct)
          throw std::runtime_error("the direct solver " + name +
                                   " is not available in Trilinos");
        check_amesos(direct->SymbolicFactorization(), "symbolic", direct.get());
        factored         = &M;
        factored_entries = M.NumGlobalNonzeros64();
      }
    check_amesos(direct->NumericFactorization(), "numeric", direct.get());
  }

  void
  LinearSolver::initialize(
    const TrilinosWrappers::SparseMatrix             &A,
    const std::vector<TrilinosWrappers::MPI::Vector> &modes,
    const std::function<void()>                      &release)
  {
    matrix = &A;
    fallback.clear();
    if (kind == "direct")
      {
        factorize(A);
        return;
      }

    // The previous hierarchy (and condensed matrix) go first: with both
    // generations alive the peak memory of a 1e6-DoF 3D contact scene grew
    // by about a third.
    amg.reset();
    null_space.reset();
    // GMRES's Krylov vectors stay in deal.II's vector pool after a solve
    // (a fifth of the matrix's memory with a restart of 100 in 3D); they go
    // back before the hierarchy is built, the peak of a run.
    GrowingVectorMemory<TrilinosWrappers::MPI::Vector>::release_unused_memory();
    // Hard contact: AMG works on the displacement system that remains
    // once the multipliers are eliminated. Where a Jacobian's multipliers
    // cannot be (a closed slave node without free displacement), that
    // Jacobian goes to the direct solver; the next one tries the
    // elimination again.
    if (condensation)
      try
        {
          condensation->condense(A);
        }
      catch (const MultiplierCondensation::NotCondensable &e)
        {
          fallback = e.what();
          factorize(A);
          return;
        }
    // The factorization of an earlier fallback refers to a matrix the
    // caller may now release.
    direct.reset();
    direct_problem.reset();
    factored = nullptr;
    // From here on AMG on the condensed system does not read A: the
    // caller may free it before the hierarchy, the peak of a 3D run, is
    // built (A is not used below then).
    if (condensation && release)
      release();
    const Epetra_RowMatrix &M =
      condensation ?
        static_cast<const Epetra_RowMatrix &>(condensation->matrix()) :
        static_cast<const Epetra_RowMatrix &>(A.trilinos_matrix());

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    Teuchos::ParameterList              list;
    std::unique_ptr<Epetra_MultiVector> constant_modes;
    data.set_parameters(list, constant_modes, M);
    // Plain (unsmoothed) aggregation: the tentative prolongator is not
    // smoothed, so the coarse operators keep the stencil of the fine one.
    // Measured on the 3D sphere-on-block Hertz scene with mortar (study/
    // contact_3d.py, doc/performance.md): at 1.1e5 DoFs 769 instead of
    // 1079 MiB and 32 instead of 44 s, GMRES iterations 273 against 267.
    list.set("aggregation: damping factor", 0.);
    // The Chebyshev smoother needs the largest eigenvalue of D^{-1} M. ML
    // estimates it by default with CG (Lanczos), which assumes a symmetric
    // matrix; the condensed contact system is not symmetric (the closed
    // nodes' constraint rows), and there the estimate fell short, the
    // smoother amplified the modes above it, and GMRES stalled. Measured
    // on the 2D elastic Hertz scene (hertz-2d-elastic.prm, node to
    // surface, 2 steps): with 6 and 4 local refinements 3244 and 2403
    // GMRES iterations per step with CG, 370 and 322 with the power
    // method, the same Newton iterations; with 7 and 5 the CG estimate
    // made GMRES stall in 92 solves and the run failed after 6 cut-backs
    // (252 s), the power method finished without cut-back (6 s). On the
    // 3D mortar Hertz scene (study/contact_3d.py, 35 000 and 1.1e5 DoFs)
    // both take about the same GMRES iterations (214 against 226, 319
    // against 283) and time. A slave 1e6 times stiffer than its master
    // (3D mortar, 16 x 8 x 16 block) failed with CG's estimate (13
    // cut-backs) and now takes the direct solver's Newton iterations.
    if (condensation)
      list.set("eigen-analysis: type", std::string("power-method"));
    // Aggregate nodes, not single DoFs: a node's displacement components
    // are consecutive DoFs (deal.II's numbering of FESystem, not
    // renumbered) and every process owns whole nodes. Six rigid-body modes
    // in 3D, three (plane) or two (axisymmetric) in 2D. Measured on the 3D
    // sphere-on-block Hertz scene with mortar at 35 000 DoFs (study/
    // contact_3d.py): peak memory 11 MiB lower, GMRES iterations 226
    // against 223.
    const int components = modes.size() == 6 ? 3 : 2;
    if (dealii::Utilities::MPI::max(M.NumMyRows() % components, comm) == 0)
      list.set("PDE equations", components);
    // Replace the constant modes by the rigid-body modes of elasticity
    // (rotated into the frames of the closed slave nodes if condensed).
    if (condensation)
      null_space = condensation->rotated_modes(modes);
    else
      {
        const auto &map = A.trilinos_matrix().RowMap();
        null_space = std::make_unique<Epetra_MultiVector>(map, modes.size());
        for (unsigned int m = 0; m < modes.size(); ++m)
          for (int i = 0; i < map.NumMyElements(); ++i)
            (*null_space)[m][i] = modes[m][map.GID(i)];
      }
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", null_space->NumVectors());
    list.set("null space: vectors", null_space->Values());
    amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg->initialize(M, list);
  }

  unsigned int
  LinearSolver::solve(const TrilinosWrappers::MPI::Vector &b,
                      TrilinosWrappers::MPI::Vector       &x,
                      const double                         relative_tolerance)
  {
    last_inexact = 0.;
    last_stalled = false;
    if (kind == "direct" || !fallback.empty())
      {
        direct_problem->SetLHS(&x.trilinos_vector());
        direct_problem->SetRHS(const_cast<Epetra_MultiVector *>(
          static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
        check_amesos(direct->Solve(), "solve", direct.get());
        return 1;
      }
    StallingControl control(parameters.maximum_iterations,
                            std::max(1e-14,
                                     std::min(relative_tolerance,
                                              parameters.relative_tolerance)) *
                              b.l2_norm());
    // Right preconditioning: GMRES then measures the true residual b - A x,
    // in the units of b, against a tolerance relative to |b|. (With left
    // preconditioning deal.II measures the preconditioned residual, in the
    // units of x: the test compared displacements with forces, and every
    // solve failed once the moduli were 1e12, as in SI units.)
    SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
      control,
      SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(
        100, /*right_preconditioning=*/true));
    x = 0;
    TrilinosWrappers::MPI::Vector cb, cx;
    double                        rhs_norm = b.l2_norm();
    last_inexact                           = 0.;
    last_stalled                           = false;
    try
      {
        if (condensation)
          {
            condensation->condense_rhs(b, cb);
            cx.reinit(cb);
            rhs_norm = cb.l2_norm();
            control.set_tolerance(
              std::max(1e-14,
                       std::min(relative_tolerance,
                                parameters.relative_tolerance)) *
              rhs_norm);
            gmres.solve(EpetraOperator{condensation->matrix()}, cx, cb, *amg);
          }
        else
          gmres.solve(*matrix, x, b, *amg);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        // GMRES stalled or reached its iteration limit; it leaves its last
        // iterate in the solution. Where it has cut the residual by at
        // least inexact_limit, that iterate is a good inexact Newton step
        // (the Newton iteration still converges, and its own residual
        // test, not this one, decides convergence). Seen on the 2D elastic
        // Hertz scene with AMG: in the last Newton iteration (a nearly
        // singular Jacobian: the cylinder's rotation about its centre is
        // resisted only through the contact zone's width) GMRES stalled at
        // 3e-8 against 1e-8, and the last load step was cut back to the
        // limit; now it takes the direct solver's Newton iterations. Every
        // process sees the same global norms, so all take the same branch.
        const double reached = rhs_norm > 0. ? e.last_residual / rhs_norm : 0.;
        if (!(reached <= inexact_limit))
          {
            std::ostringstream text;
            text << "the linear solver (GMRES with AMG) did not converge ("
                 << (control.stalled() ? "stalled after " : "stopped after ")
                 << e.last_step << " iterations): it reduced the residual to "
                 << std::scientific << std::setprecision(2) << reached
                 << " of its start, against the tolerance "
                 << control.tolerance() / (rhs_norm > 0. ? rhs_norm : 1.)
                 << " (raise 'Linear solver/Maximum iterations', or use "
                    "'Linear solver/Type = direct')";
            throw std::runtime_error(text.str());
          }
        last_inexact = reached;
        last_stalled = control.stalled();
      }
    if (condensation)
      condensation->expand(b, cx, x);
    return control.last_step();
  }
} // namespace glide
