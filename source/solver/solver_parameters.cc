#include <glide/scene/input_error.h>
#include <glide/solver/solver_parameters.h>

namespace glide
{
  using namespace dealii;

  void
  NonlinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry("Strategy",
                      "automatic",
                      Patterns::Selection("automatic|newton|line search"),
                      "KINSOL strategy: 'newton' takes full Newton steps, "
                      "'line search' backtracks when the residual grows. "
                      "automatic: newton in scenes with contact (the "
                      "complementarity function is only semismooth, and "
                      "KINSOL's line search stalls at active-set changes), "
                      "and a load step that fails with it (no convergence, "
                      "active-set cycling, an inverted element) is tried "
                      "once more with line search, from the same initial "
                      "guess, before it is cut back; line search "
                      "otherwise.");
    prm.declare_entry("Tolerance",
                      "1e-10",
                      Patterns::Double(0.),
                      "Convergence when the max-norm of the residual, "
                      "scaled by 1/(E_min A_ref) with E_min the softest "
                      "deformable body's Young's modulus and A_ref the mean "
                      "boundary-face measure, is below this. Unit-free: the "
                      "same value works in SI and in mm-N-MPa. 1e-8 to 1e-12 "
                      "are sensible; at most 1e-6 (a load step's first "
                      "iterate often has 1e-6 to 1e-3, so a looser one "
                      "accepts unconverged states). Where the loads, "
                      "prescribed displacements and rigid masters' motions "
                      "strain the bodies by less than 1e-6, the tolerance "
                      "is multiplied by that strain / 1e-6, so that the "
                      "residual left is at most 1e6 x this of the largest "
                      "load (the log says so).");
    prm.declare_entry("Maximum iterations",
                      "25",
                      Patterns::Integer(1, 1000),
                      "Newton iterations per load step before the step is "
                      "cut back.");
    prm.declare_entry("Maximum setup calls",
                      "1",
                      Patterns::Integer(1, 100),
                      "Newton iterations between Jacobian assemblies (1: "
                      "assemble every iteration, the safe choice).");
    prm.leave_subsection();
  }

  void
  NonlinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    strategy                         = prm.get("Strategy");
    tolerance                        = prm.get_double("Tolerance");
    maximum_iterations               = prm.get_integer("Maximum iterations");
    maximum_setup_calls              = prm.get_integer("Maximum setup calls");
    const std::string tolerance_text = prm.get("Tolerance");
    prm.leave_subsection();
    require(tolerance > 0.,
            "Parameter 'Nonlinear solver/Tolerance' = " + tolerance_text +
              " must be positive: round-off leaves every residual above 0, "
              "so no load step could converge. Use 1e-8 to 1e-12.");
    require(tolerance <= 1e-6,
            "Parameter 'Nonlinear solver/Tolerance' = " + tolerance_text +
              " is outside (0, 1e-6]: the scaled residual of a load "
              "step's first iterate is often 1e-6 to 1e-3, so a looser "
              "tolerance accepts a state that is not in equilibrium as "
              "converged. Use 1e-8 to 1e-12.");
  }

  void
  LinearSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type",
                      "automatic",
                      Patterns::Selection("automatic|direct|amg"),
                      "direct: sparse LU (see 'Direct solver'). amg: GMRES "
                      "preconditioned by Trilinos ML algebraic multigrid "
                      "with rigid-body modes, for large 3D problems; with "
                      "hard contact it solves the displacement system left "
                      "once the contact multipliers are eliminated (node to "
                      "surface and mortar; a Jacobian where a slave node "
                      "without free displacement is closed goes to the "
                      "direct solver; doc/theory/mortar.md). automatic: "
                      "direct in 2D and for 3D problems up to 'Automatic "
                      "direct limit' DoFs, amg above (direct, with a note in "
                      "the log, where hard contact cannot be condensed).");
    prm.declare_entry("Direct solver",
                      "MUMPS",
                      Patterns::Selection("MUMPS|KLU"),
                      "Amesos direct solver: MUMPS (fast, parallel) or KLU.");
    prm.declare_entry("Automatic direct limit",
                      "200000",
                      Patterns::Integer(0),
                      "With 'Type = automatic', 3D problems with more DoFs "
                      "than this use amg.");
    prm.declare_entry("Relative tolerance",
                      "1e-8",
                      Patterns::Double(0., 0.5),
                      "Relative residual reduction of the Krylov solver "
                      "(at most 0.5: at 1 the solver returns no correction "
                      "and Newton's iterates become NaN); KINSOL's inexact "
                      "Newton may ask for a tighter one.");
    prm.declare_entry("Maximum iterations",
                      "2000",
                      Patterns::Integer(1),
                      "Krylov iterations before the linear solve stops. "
                      "GMRES also stops where it stalls (the residual falls "
                      "by less than a tenth over 200 iterations). A solve "
                      "that stopped after reducing the residual to 1e-3 of "
                      "its start or less is taken as an inexact Newton step "
                      "(the log says so; Newton's own tolerance decides "
                      "convergence); otherwise the Newton step fails.");
    prm.leave_subsection();
  }

  void
  LinearSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    type                   = prm.get("Type");
    direct_solver          = prm.get("Direct solver");
    automatic_direct_limit = prm.get_integer("Automatic direct limit");
    relative_tolerance     = prm.get_double("Relative tolerance");
    maximum_iterations     = prm.get_integer("Maximum iterations");
    prm.leave_subsection();
  }

  void
  LoadSteppingParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Load stepping");
    prm.declare_entry("Number of steps",
                      "1",
                      Patterns::Integer(1, 100000),
                      "Equal load steps from t = 0 to t = 1; t is the "
                      "variable of every boundary-condition function.");
    prm.declare_entry("Maximum cut-backs",
                      "6",
                      Patterns::Integer(0, 30),
                      "How often one load step may be cut back and retried "
                      "before the run stops (statistics.csv counts the "
                      "cut-backs of the whole run). The increment also "
                      "never falls below 1 / 'Number of steps' x 'Cut-back "
                      "factor' ^ 'Maximum cut-backs': a step that fails "
                      "there ends the run.");
    prm.declare_entry("Cut-back factor",
                      "0.5",
                      Patterns::Double(0.01, 0.9),
                      "Factor applied to the step size after a failure.");
    prm.declare_entry(
      "Predictor",
      "tangent",
      Patterns::Selection("tangent|none"),
      "Initial guess of a load step that changes prescribed displacements. "
      "'tangent': one linear solve with the Jacobian of the last converged "
      "state carries the increment of the prescribed displacements and "
      "loads into the whole body (Abaqus' first iteration), so that the "
      "elements next to the prescribed nodes are not distorted or inverted; "
      "it costs one Jacobian and one linear solve, not counted in the "
      "Newton iterations (steps with loads only need none: KINSOL's first "
      "iteration is that solve); the prediction is kept only where its "
      "residual is no larger than that of the 'none' start. 'none': the "
      "last converged state with the new prescribed values.");
    prm.leave_subsection();
  }

  void
  LoadSteppingParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Load stepping");
    number_of_steps   = prm.get_integer("Number of steps");
    maximum_cut_backs = prm.get_integer("Maximum cut-backs");
    cut_back_factor   = prm.get_double("Cut-back factor");
    tangent_predictor = prm.get("Predictor") == "tangent";
    prm.leave_subsection();
  }
} // namespace glide
