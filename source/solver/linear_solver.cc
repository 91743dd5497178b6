#include <glide/solver/linear_solver.h>

#include <deal.II/lac/solver_gmres.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

namespace glide
{
  using namespace dealii;

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
    return kind == "direct" ?
             "direct (Amesos " + parameters.direct_solver + ")" :
             "GMRES with ML algebraic multigrid";
  }

  void
  LinearSolver::initialize(
    const TrilinosWrappers::SparseMatrix             &A,
    const std::vector<TrilinosWrappers::MPI::Vector> &modes)
  {
    matrix = &A;
    if (kind == "direct")
      {
        direct = std::make_unique<TrilinosWrappers::SolverDirect>(
          direct_control,
          TrilinosWrappers::SolverDirect::AdditionalData(
            false,
            parameters.direct_solver == "MUMPS" ? "Amesos_Mumps" :
                                                  "Amesos_Klu"));
        direct->initialize(A);
        return;
      }

    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.higher_order_elements = false;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    Teuchos::ParameterList              list;
    std::unique_ptr<Epetra_MultiVector> constant_modes;
    data.set_parameters(list, constant_modes, A);
    // Replace the constant modes by the rigid-body modes of elasticity.
    const auto &map = A.trilinos_matrix().RowMap();
    null_space      = std::make_unique<Epetra_MultiVector>(map, modes.size());
    for (unsigned int m = 0; m < modes.size(); ++m)
      for (int i = 0; i < map.NumMyElements(); ++i)
        (*null_space)[m][i] = modes[m][map.GID(i)];
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", null_space->NumVectors());
    list.set("null space: vectors", null_space->Values());
    amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg->initialize(A, list);
  }

  unsigned int
  LinearSolver::solve(const TrilinosWrappers::MPI::Vector &b,
                      TrilinosWrappers::MPI::Vector       &x,
                      const double                         relative_tolerance)
  {
    if (kind == "direct")
      {
        direct->solve(x, b);
        return 1;
      }
    SolverControl control(parameters.maximum_iterations,
                          std::max(1e-14,
                                   std::min(relative_tolerance,
                                            parameters.relative_tolerance)) *
                            b.l2_norm());
    SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
      control, SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(100));
    x = 0;
    try
      {
        gmres.solve(*matrix, x, b, *amg);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        throw std::runtime_error(
          "the linear solver (GMRES with AMG) did not converge in " +
          std::to_string(e.last_step) + " iterations (residual " +
          std::to_string(e.last_residual) + ")");
      }
    return control.last_step();
  }
} // namespace glide
