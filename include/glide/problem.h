#pragma once

#include <glide/contact/active_set_monitor.h>
#include <glide/contact/contact.h>
#include <glide/mechanics/elasticity.h>
#include <glide/output/contact_output.h>
#include <glide/output/output_directory.h>
#include <glide/output/statistics.h>
#include <glide/output/vtu_writer.h>
#include <glide/scene/scene.h>
#include <glide/solver/linear_solver.h>
#include <glide/solver/nonlinear_solver.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/timer.h>

#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

namespace glide
{
  /**
   * One run of a scene (DESIGN.md, "How one solve flows"): set up the
   * bodies, then for each load step let KINSOL solve F(U) = 0, cutting the
   * step back when it fails, and after each converged step write the
   * statistics row and the VTU file. Returns normally when the last step
   * converged; throws std::runtime_error with the reason when a step fails
   * after all cut-backs, and InputError for mistakes in the scene. With
   * @p check_only (`glide --check`) it stops after the set-up and its
   * checks: the summary and the warnings are printed, nothing is solved or
   * written.
   */
  template <int dim>
  void
  run_scene(const Scene &scene, MPI_Comm comm, bool check_only = false);

  /**
   * The problem of one scene and its load stepper: the bodies, the contact
   * pairs, the nonlinear and linear solvers and the output, with one
   * function per stage of the run. The residual KINSOL sees is a function
   * of the iterate and of what the stepper fixes between solves (the load
   * factor, the contact holds), never of the history of a solve (R16.1).
   */
  template <int dim>
  class Problem
  {
  public:
    Problem(const Scene                &scene,
            MPI_Comm                    comm,
            dealii::ConditionalOStream &pcout,
            dealii::TimerOutput        &timer);

    /// The bodies' VTU file of converged step @p step (state U at load
    /// factor t, contact forces included), listed in the .pvd once the
    /// caller commits the step.
    void
    write_bodies(unsigned int step);

    /// Every load step to the end (or an exception); with @p check_only
    /// the set-up, its checks and the summary only.
    void
    run(bool check_only = false);

  private:
    /// Bodies, contact pairs, the system's layout, the solvers' choice.
    void
    setup();
    /// The scene summary at the top of the log.
    void
    print_summary() const;
    /// The output directory (cleared of this scene's earlier results), the
    /// statistics table and the VTU writer; only after every input check.
    void
    prepare_output();
    /// The callbacks through which KINSOL sees the problem.
    void
    setup_callbacks();
    /// The scaled residual below which round-off leaves nothing to
    /// reduce: the larger of the bodies' (Elasticity::round_off_floor())
    /// and the contact gaps' (Contact::round_off_floor()).
    double
    round_off_floor() const;
    /// Rebuild the sparsity pattern and the Jacobian (sliding contact).
    void
    rebuild_pattern();
    /// Under MPI, where the slave nodes or the master slid far since the
    /// master facets were gathered: gather them again around @p u and
    /// rebuild the pattern (Contact::follow()), before a residual at @p u
    /// that is not KINSOL's next (a new attempt, the predictor's check).
    void
    follow(const VectorType &u);
    /// Tangent predictor ('Load stepping/Predictor'): one linear solve from
    /// the converged state @p U0 carries the increment of the prescribed
    /// values in @p U_trial into the bodies; kept only where it lowers the
    /// scaled residual.
    void
    predict(const VectorType &U0, const double t_new, VectorType &U_trial);
    /// Solve one load step from @p U_trial: full Newton steps, then, if
    /// that fails, once more with line search, holding the contact nodes
    /// that alternated between two facets in the first attempt.
    NonlinearSolver::Result
    solve_step(VectorType &U_trial);
    /// Statistics row, contact output and VTU of converged step @p step.
    void
    postprocess(const unsigned int             step,
                const double                   t_old,
                const NonlinearSolver::Result &result,
                const unsigned int             cut_backs,
                const double                   wall_time);
    /// timings.csv and the closing line of the log.
    void
    finish(const unsigned int steps,
           const unsigned int cut_backs,
           const double       wall_time);

    const Scene                &scene;
    MPI_Comm                    comm;
    dealii::ConditionalOStream &pcout;
    dealii::TimerOutput        &timer;

    Elasticity<dim> elasticity;
    Contact<dim>    contact;
    /// The Jacobian outlives the linear solver: Amesos keeps a pointer.
    MatrixType                       jacobian;
    LinearSolver                     linear_solver;
    std::vector<VectorType>          modes;
    NonlinearSolver::Callbacks       callbacks;
    std::unique_ptr<NonlinearSolver> newton, damped;
    VectorType                       residual_scale, solution_scale;
    ActiveSetMonitor<dim>            monitor;
    /// Scaled residuals of the running solve: at its first iterate and at
    /// the last one reported (the Jacobian stabilization's scale).
    double       first_residual    = 0.;
    double       last_residual     = 0.;
    double       previous_residual = 0.; ///< the iterate's before the last
    unsigned int last_iteration    = 0;
    /// Whether the last Jacobian went to the direct solver although AMG
    /// was chosen (LinearSolver::fallback_reason()): the log notes changes.
    bool                                direct_fallback = false;
    std::string                         directory;
    std::unique_ptr<OutputDirectory>    output;
    std::unique_ptr<Statistics>         statistics;
    std::unique_ptr<VtuWriter<dim>>     vtu;
    std::unique_ptr<ContactWriter<dim>> contact_output;
    VectorType                          U;
    /// Load factor of the step being solved.
    double t = 0.;
    /// Whether the current attempt ends as soon as a slave node alternates
    /// between two facets (so that the next one can hold it).
    bool stop_on_alternation = true;
    /// Loads that strain the bodies by less than this get a tolerance
    /// relative to them (setup()).
    static constexpr double small_strain = 1e-6;
    /// The factor on 'Nonlinear solver/Tolerance' for such loads, 1 else.
    double tolerance_factor = 1.;
    /// The largest strain the loads, prescribed displacements and moving
    /// analytical masters impose (Elasticity::driving_strain(),
    /// Contact::largest_master_motion() over the scene's size).
    double driving_strain = 0.;
    /// The round-off floor the Newton solver uses (setup()).
    double newton_floor = 0.;
    /// Whether an attempt of the current load step ended with nodes
    /// cycling where the master ends inside their slave facets (the
    /// step's failure message then says what to do).
    bool corner_cycling = false;
    /// The iterate at which an attempt stopped for alternating nodes.
    VectorType restart;
    bool       have_restart = false;
    /// A step whose held nodes' gaps (to their facet's plane) differ from
    /// their gaps to the master by more than this fraction of the facet's
    /// length fails (solve_step()): the held problem's answer is then not
    /// the scene's (the node has left the corner it alternated at).
    static constexpr double max_held_gap_error = 0.01;
    /// A step whose held nodes' gap errors may move their nodal forces by
    /// more than this fraction of their pair's largest nodal force fails
    /// (solve_step(); Contact::held_force_effect()). The gap error alone
    /// did not tell: at a fine mesh's contact pressure 0.1 % of a facet
    /// is 15 % of the peak nodal force, while degree 2 at level 0 of the
    /// robustness matrix converged steps whose held nodes could move it
    /// by 54 %.
    static constexpr double max_held_force_effect = 0.05;
  };
} // namespace glide
