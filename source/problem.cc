#include <glide/output/interruption.h>
#include <glide/output/output_error.h>
#include <glide/problem.h>
#include <glide/scene/input_error.h>
#include <glide/solver/linear_solver.h>
#include <glide/solver/load_stepper.h>
#include <glide/solver/nonlinear_solver.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <sys/resource.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /**
     * Warnings about the bodies from mesh files: the reader's (duplicate
     * nodes), and element types that say another analysis than the
     * scene's. Abaqus 2D element types say what the analysis is (CAX,
     * CGAX: axisymmetric; CPE, CPEG: plane strain; CPS: plane stress);
     * glide takes it from the scene's 'Analysis type' (doc/mesh-import.md).
     */
    std::vector<std::string>
    mesh_notes(const Scene &scene)
    {
      // The names that the scene's boundary conditions and contact pairs
      // give (surfaces and node sets): a node set's warning is for the
      // log only where the scene uses the set (a file's unused set with
      // mid-side nodes warned at every run until 2026-12-07).
      std::set<std::string> named;
      const auto            name = [&](const std::string &list) {
        named.insert(Utilities::trim(list));
        for (const auto &n : Utilities::split_string_list(list, ','))
          named.insert(n);
      };
      for (const auto &bc : scene.boundary_conditions)
        name(bc.surface);
      for (const auto &cp : scene.contact_pairs)
        {
          name(cp.slave);
          name(cp.master);
          for (const auto &[set, normal] : cp.master_normals)
            named.insert(set);
        }
      std::vector<std::string> notes;
      for (const auto &body : scene.bodies)
        {
          if (!body.mesh.imported)
            continue;
          for (const auto &note : body.mesh.imported->notes)
            notes.push_back("body '" + body.name + "': " + note);
          for (const auto &[set, note] : body.mesh.imported->node_set_notes)
            if (named.count(body.name + "." + set))
              notes.push_back("body '" + body.name + "': " + note);
          std::string axisymmetric, plane, plane_stress;
          for (std::string type : body.mesh.imported->element_types)
            {
              for (auto &c : type)
                c = std::toupper(static_cast<unsigned char>(c));
              const auto starts = [&](const char *prefix) {
                return type.rfind(prefix, 0) == 0;
              };
              std::string *list = nullptr;
              if (starts("CAX") || starts("CGAX"))
                list = &axisymmetric;
              else if (starts("CPS"))
                list = &plane_stress;
              else if (starts("CPE"))
                list = &plane;
              if (list)
                *list += (list->empty() ? "" : ", ") + type;
            }
          const std::string head = "body '" + body.name + "': the mesh file '" +
                                   body.mesh.imported->file +
                                   "' has elements of type ";
          if (scene.analysis == AnalysisType::plane_strain &&
              !axisymmetric.empty())
            notes.push_back(
              head + axisymmetric +
              ", axisymmetric in Abaqus, but the scene's 'Analysis type' is "
              "plane strain, which glide uses; set 'Analysis type = "
              "axisymmetric' for an axisymmetric model (x the radius, y the "
              "axis).");
          if (scene.analysis == AnalysisType::plane_strain &&
              !plane_stress.empty())
            notes.push_back(
              head + plane_stress +
              ", plane stress in Abaqus; glide has no plane stress: the "
              "results are plane strain (the scene's 'Analysis type').");
          if (scene.analysis == AnalysisType::axisymmetric &&
              !(plane + plane_stress).empty())
            notes.push_back(
              head + plane +
              (plane.empty() || plane_stress.empty() ? "" : ", ") +
              plane_stress +
              ", plane elements in Abaqus, but the scene's 'Analysis type' "
              "is axisymmetric, which glide uses (x the radius, y the axis); "
              "set 'Analysis type = plane strain' for a plane model.");
        }
      return notes;
    }

    /// Peak resident memory of this process in MiB, summed over processes
    /// (@p largest: the largest of one process).
    double
    peak_memory_mib(MPI_Comm comm, const bool largest = false)
    {
      rusage usage;
      getrusage(RUSAGE_SELF, &usage);
      return largest ? Utilities::MPI::max(usage.ru_maxrss / 1024., comm) :
                       Utilities::MPI::sum(usage.ru_maxrss / 1024., comm);
    }

    std::string
    scientific(const double x, const int digits = 3)
    {
      std::ostringstream s;
      s << std::scientific << std::setprecision(digits) << x;
      return s.str();
    }
  } // namespace

  template <int dim>
  Problem<dim>::Problem(const Scene        &scene,
                        MPI_Comm            comm,
                        ConditionalOStream &pcout,
                        TimerOutput        &timer)
    : scene(scene)
    , comm(comm)
    , pcout(pcout)
    , timer(timer)
    , elasticity(scene, comm, timer)
    , contact(scene, elasticity, comm)
    , linear_solver(scene.linear_solver, comm)
  {}

  template <int dim>
  void
  Problem<dim>::setup()
  {
    elasticity.setup(); // every input check happens here, before output
    {
      TimerOutput::Scope t(timer, "setup");
      contact.setup(elasticity.get_dof_handler().n_dofs());
    }
    elasticity.setup_system(
      contact.owned_multipliers(),
      [&](DynamicSparsityPattern &dsp) { contact.add_sparsity(dsp); },
      contact.ghost_dofs());
    jacobian.reinit(elasticity.matrix_pattern());
    // Input checks that need the constraints: every body held, every
    // function finite (before anything is written).
    elasticity.check_inputs();
    // Hard contact adds multipliers: the direct solver takes the whole
    // saddle-point system; AMG takes the displacement system left once they
    // are eliminated (MultiplierCondensation), where that is possible.
    const bool  saddle_point = contact.n_multipliers() > 0;
    std::string why_not;
    auto        blocks      = saddle_point ?
                                contact.condensable_multipliers(why_not) :
                                decltype(contact.condensable_multipliers(why_not))();
    const bool  condensable = saddle_point && why_not.empty();
    require(
      !(saddle_point && !condensable && scene.linear_solver.type == "amg"),
      "In scene file '" + scene.file +
        "': 'Linear solver/Type = amg' cannot solve this scene's hard contact: " +
        why_not +
        ", so its multipliers cannot be eliminated. Use 'direct' (or "
        "'automatic'), or 'Enforcement = penalty'.");
    const auto &dof_handler = elasticity.get_dof_handler();
    if (linear_solver.choose(dim,
                             saddle_point && !condensable ?
                               0 :
                               dof_handler.n_dofs()) == "amg")
      {
        modes = elasticity.rigid_body_modes();
        if (saddle_point)
          {
            std::vector<MultiplierCondensation::Block> b;
            for (auto &[m, dofs] : blocks)
              b.push_back({m, std::move(dofs)});
            linear_solver.set_condensation(
              std::make_unique<MultiplierCondensation>(
                std::move(b),
                dof_handler.n_dofs(),
                elasticity.locally_owned(),
                comm));
          }
      }
    else if (saddle_point && !condensable &&
             scene.linear_solver.type == "automatic" &&
             dof_handler.n_dofs() >
               scene.linear_solver.automatic_direct_limit &&
             dim == 3)
      pcout << "Note: the direct solver, not AMG, for this 3D scene: "
            << why_not << ", so the contact multipliers cannot be eliminated."
            << std::endl;

    const auto &owned = elasticity.locally_owned();
    U.reinit(owned, comm);
    // KINSOL's scalings: force rows by 1/(E_min A_ref), displacements by
    // 1/L, contact rows and forces by 1/(E_pair A_ref) with E_pair the
    // pair's contact modulus.
    residual_scale.reinit(owned, comm);
    solution_scale.reinit(owned, comm);
    residual_scale = elasticity.residual_scale();
    solution_scale = 1. / elasticity.length_scale();
    contact.set_scaling(residual_scale, solution_scale);

    NonlinearSolverParameters newton_parameters = scene.nonlinear_solver;
    newton_parameters.round_off_floor           = round_off_floor();
    // The tolerance is a strain (residual over E_min A_ref): loads that
    // strain the bodies by less than it were 'converged' at U = 0 (a
    // silicon beam under its own weight, strain 1e-13: zero sag, exit 0).
    // Where the loads and prescribed displacements strain the bodies by
    // less than 1e-6, the tolerance and the bodies' round-off floor shrink
    // with them, so that the residual left is at most tolerance x 1e6 of
    // the largest load (1e-4 at the default). An analytical rigid master
    // presses into the bodies by at most its motion next to the slave
    // nodes, which counts like a prescribed displacement (its motion
    // across an initial gap too, which keeps the tolerance as given).
    const double first  = 1. / scene.load_stepping.number_of_steps;
    driving_strain      = std::max(elasticity.driving_strain(),
                              contact.largest_master_motion({first, 1.}) /
                                elasticity.length_scale());
    const double strain = driving_strain;
    if (strain > 0. && strain < small_strain)
      {
        tolerance_factor = strain / small_strain;
        newton_parameters.tolerance *= tolerance_factor;
        newton_parameters.step_tolerance *= tolerance_factor;
        // The linear law's round-off falls with the strain; the
        // neo-Hookean law's does not (it forms F = I + H and its inverse,
        // which keep about 16 digits of I, not of H): there the floor
        // stays, and a step at the round-off of I is accepted at it.
        if (!scene.geometric_nonlinearity)
          newton_parameters.round_off_floor =
            std::max(elasticity.round_off_floor() * tolerance_factor,
                     contact.round_off_floor());
      }
    newton_parameters.linear_problem =
      !contact.active() && !scene.geometric_nonlinearity;
    newton_floor = newton_parameters.round_off_floor;
    newton       = std::make_unique<NonlinearSolver>(newton_parameters, comm);
    NonlinearSolverParameters damped_parameters = newton_parameters;
    damped_parameters.strategy                  = "line search";
    damped = std::make_unique<NonlinearSolver>(damped_parameters, comm);
    setup_callbacks();
  }

  template <int dim>
  void
  Problem<dim>::print_summary() const
  {
    const auto &dof_handler = elasticity.get_dof_handler();
    pcout << "glide: scene '" << scene.name << "' (" << scene.file << ")\n"
          << "  analysis:       " << scene.analysis_name() << ", " << dim
          << "D, degree " << scene.degree
          << (scene.geometric_nonlinearity ? ", geometrically nonlinear" :
                                             ", geometrically linear")
          << "\n"
          << "  bodies:         " << scene.bodies.size() << ", "
          << elasticity.get_triangulation().n_global_active_cells()
          << " cells, " << dof_handler.n_dofs() << " DoFs on "
          << Utilities::MPI::n_mpi_processes(comm) << " process(es)\n"
          << "  surfaces:       " << elasticity.get_mesh().surface_list()
          << "\n"
          << "  linear solver:  " << linear_solver.description() << "\n"
          << "  active effects: ";
    auto effects = elasticity.active_effects();
    for (const auto &e : contact.active_effects())
      effects.push_back(e);
    for (unsigned int i = 0; i < effects.size(); ++i)
      pcout << (i ? "; " : "") << effects[i];
    pcout << std::endl;
    if (tolerance_factor < 1.)
      pcout << "  note: the loads, prescribed displacements and rigid masters' "
               "motions strain the "
               "bodies by at most "
            << driving_strain
            << "; 'Nonlinear solver/Tolerance' is taken relative to that "
               "(x "
            << tolerance_factor << ": "
            << scene.nonlinear_solver.tolerance * tolerance_factor
            << "), so that the residual left is at most "
            << scene.nonlinear_solver.tolerance / small_strain
            << " of the largest load." << std::endl;
    // Loads declared but zero (a 'Function' of '0; 0'): the scene's
    // solution is zero at the first and the last step, which a user
    // rarely means (a scene that declares no load at all is refused).
    // Not with contact: an initial overlap loads the bodies.
    // Also loads that act only on DoFs a displacement condition holds
    // (their reactions take them): the same zero solution (until
    // 2026-12-07 the warning said such loads were zero).
    if (driving_strain == 0. && scene.contact_pairs.empty())
      pcout << "  warning: the loads and prescribed displacements leave the "
               "bodies unloaded at the first and the last load factor: the "
               "loads ('Function' of the traction, pressure and force "
               "conditions, 'Body force') are zero there or act only where "
               "a displacement condition holds the nodes (its reaction then "
               "takes them), and the prescribed displacements and rigid-body "
               "motions are zero; the displacements there are zero. Check "
               "the loads' 'Function' and 'Surface' entries."
            << std::endl;
    for (const auto &note : scene.unused)
      pcout << "  warning: " << note << std::endl;
    for (const auto &note : mesh_notes(scene))
      pcout << "  warning: " << note << std::endl;
    for (const auto &note : elasticity.get_mesh().notes())
      pcout << "  warning: " << note << std::endl;
    for (const auto &note : elasticity.condition_warnings())
      pcout << "  warning: " << note << std::endl;
  }

  template <int dim>
  void
  Problem<dim>::prepare_output()
  {
    // Output goes to <directory>/<scene name>/; only now, after all checks.
    output = std::make_unique<OutputDirectory>(scene.output.directory,
                                               scene.name,
                                               comm);
    output->prepare();
    directory  = output->path();
    statistics = std::make_unique<Statistics>(*output, comm);
    vtu = std::make_unique<VtuWriter<dim>>(elasticity, *output, scene.name);
    // Contact output goes to the staging directory; commit_step() moves
    // it into place with the step's indexes.
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      contact_output = std::make_unique<ContactWriter<dim>>(output->staging());
  }

  template <int dim>
  void
  Problem<dim>::follow(const VectorType &u)
  {
    if (contact.active() && contact.follow(u))
      {
        // The new ghost DoFs' constraints come with the new pattern.
        contact.needs_new_pattern(u);
        rebuild_pattern();
      }
  }

  template <int dim>
  void
  Problem<dim>::rebuild_pattern()
  {
    pcout << "    contact: sparsity pattern rebuilt (sliding)" << std::endl;
    linear_solver.clear(); // it refers to the old matrix
    elasticity.setup_system(
      contact.owned_multipliers(),
      [&](DynamicSparsityPattern &dsp) { contact.add_sparsity(dsp); },
      contact.ghost_dofs());
    jacobian.reinit(elasticity.matrix_pattern());
  }

  template <int dim>
  double
  Problem<dim>::round_off_floor() const
  {
    return std::max(elasticity.round_off_floor(), contact.round_off_floor());
  }

  template <int dim>
  void
  Problem<dim>::setup_callbacks()
  {
    const auto &owned       = elasticity.locally_owned();
    callbacks.reinit_vector = [this, &owned](VectorType &v) {
      v.reinit(owned, comm);
    };
    callbacks.residual = [this](const VectorType &u, VectorType &F) {
      elasticity.residual(u, t, F);
      if (contact.active())
        {
          TimerOutput::Scope s(timer, "contact: residual");
          contact.assemble(u, &F, nullptr);
        }
    };
    callbacks.setup_jacobian = [this](const VectorType &u) {
      if (contact.active())
        {
          // The monitor sees each Newton iterate once; a node that keeps
          // switching ends the solve early (it would not converge).
          // The Jacobian-only stabilization of open nodes near the master
          // (Contact::stabilization_weight()): in full while the active set
          // changes; once it has settled, scaled by the square of the
          // solve's residual reduction (a Levenberg-Marquardt term mu_k ~
          // ||F_k||^2), so that the Jacobian's error shrinks faster than
          // the residual and Newton converges quadratically, while a free
          // rigid motion that no closed node holds (a cylinder touching at
          // one node, whose rotation only the springs resist) never leaves
          // the Jacobian singular. Switched off there, the direct solver
          // returned an arbitrary rotation from round-off, which closed
          // nodes on one side of a symmetric problem
          // (doc/theory/nonlinear-solution.md).
          const bool changed =
            Utilities::MPI::max(monitor.record(contact.status(u)) ? 1 : 0,
                                comm) > 0;
          double factor = 1.;
          if (!changed && first_residual > 0.)
            factor = std::pow(std::min(1., last_residual / first_residual), 2);
          contact.set_jacobian_stabilization(factor);
          // Nodes whose projection keeps going back and forth between two
          // facets of a faceted master: end this attempt, the next one
          // holds them (solve_step()).
          if (stop_on_alternation &&
              Utilities::MPI::sum(
                static_cast<unsigned int>(monitor.holds().size()), comm) > 0)
            {
              restart      = u;
              have_restart = true;
              throw std::runtime_error(
                "the projection of slave node(s) alternated between two "
                "master facets meeting at a corner");
            }
          const std::string cycling = monitor.cycling(comm);
          if (!cycling.empty())
            {
              // Once seen in this step, the later attempts' messages keep
              // saying so.
              corner_cycling =
                monitor.cycling_at_master_end(comm) || corner_cycling;
              throw std::runtime_error(
                "active-set cycling: slave node(s) at " + cycling +
                " switched between open and closed more than " +
                std::to_string(ActiveSetMonitor<dim>::maximum_switches) +
                " times in this load step" +
                (corner_cycling ?
                   std::string(" (the master surface ends inside their "
                               "slave facets)") :
                   std::string()));
            }
          // Full Newton steps that have raised the scaled residual more
          // than 100 times above the solve's first one, and raise it again,
          // have left the region where the active set they predict is of
          // use: end the attempt, the next one takes the line search (which
          // cannot raise it) from the step's start. A stiff slave on a soft
          // master went from 1.5e-4 up to 2.7 over 9 iterations, until the
          // cycling check ended them, where the line search needs 3. The
          // first iteration is exempt: from the active set of a first
          // contact under a force (a body pressed onto a point) it may
          // raise the residual by any factor, 190 to 380 times for the
          // axisymmetric Hertz scene, which then falls in every iteration
          // to convergence; stopped there, the line search took 4 more
          // iterations (doc/theory/nonlinear-solution.md).
          constexpr double divergence_factor = 100.;
          if (first_residual > 0. && last_iteration >= 2 &&
              last_residual > previous_residual &&
              last_residual > divergence_factor * first_residual)
            {
              std::ostringstream text;
              text << "full Newton steps diverge: scaled residual "
                   << last_residual << ", more than " << divergence_factor
                   << " times the attempt's first (" << first_residual << ")";
              throw std::runtime_error(text.str());
            }
          if (contact.needs_new_pattern(u))
            rebuild_pattern(); // a slave node slid out of the pattern
        }
      if (jacobian.m() == 0) // released after the last condensation
        jacobian.reinit(elasticity.matrix_pattern());
      elasticity.jacobian(u, jacobian);
      if (contact.active())
        {
          TimerOutput::Scope s(timer, "contact: Jacobian");
          contact.assemble(u, nullptr, &jacobian);
        }
      TimerOutput::Scope s(timer, "linear solver: setup");
      // AMG on the condensed system keeps what it needs of the Jacobian:
      // its memory (a seventh of a 3D scene's peak) goes back before the
      // hierarchy is built, until the next set-up.
      linear_solver.initialize(jacobian, modes, [this] { jacobian.clear(); });
      // AMG chosen, but this Jacobian's multipliers could not be
      // eliminated: noted when that starts and when it ends.
      if (const bool fallback = !linear_solver.fallback_reason().empty();
          fallback != direct_fallback)
        {
          direct_fallback = fallback;
          if (fallback)
            pcout << "    linear solver: the direct solver, not AMG, from "
                     "this Jacobian on: "
                  << linear_solver.fallback_reason()
                  << ", so the contact multipliers cannot be eliminated"
                  << std::endl;
          else
            pcout << "    linear solver: AMG again (the contact multipliers "
                     "can be eliminated)"
                  << std::endl;
        }
    };
    callbacks.solve_jacobian = [this](const VectorType &rhs, VectorType &dx) {
      TimerOutput::Scope s(timer, "linear solver: solve");
      const unsigned int n =
        linear_solver.solve(rhs, dx, scene.linear_solver.relative_tolerance);
      if (linear_solver.last_inexact_reduction() > 0.)
        pcout << "    linear solver: GMRES "
              << (linear_solver.last_inexact_stalled() ?
                    "stalled after " :
                    "reached its iteration limit, ")
              << n << " iterations, with the residual reduced to "
              << scientific(linear_solver.last_inexact_reduction())
              << " of its start (tolerance "
              << scientific(scene.linear_solver.relative_tolerance)
              << "); its iterate is taken as an inexact Newton step"
              << std::endl;
      elasticity.update_constraints().distribute(dx);
      return n;
    };
    callbacks.report = [this](const unsigned int k, const double r) {
      if (k == 0)
        first_residual = r;
      previous_residual = k == 0 ? r : last_residual;
      last_residual     = r;
      last_iteration    = k;
      pcout << "    iteration " << std::setw(2) << k << ": scaled residual "
            << scientific(r) << std::endl;
    };
  }

  template <int dim>
  void
  Problem<dim>::predict(const VectorType &U0,
                        const double      t_new,
                        VectorType       &U_trial)
  {
    // For steps that change prescribed displacements: one linear solve
    // with the Jacobian at the converged state U0 carries their increment
    // (in U_trial) and that of the loads into the whole body, instead of
    // KINSOL's first iteration from U_trial, where the elements next to the
    // prescribed nodes are distorted (or inverted). Without a displacement
    // increment, KINSOL's first iteration from U_trial = U0 is that very
    // solve: nothing to do.
    const auto &owned = elasticity.locally_owned();
    VectorType  D     = U_trial;
    D -= U0;
    // Round-off is no increment: distribute() recomputes the values of
    // constrained DoFs (hanging nodes) of U0 to the last bit, and a
    // prediction made for that would be an uncounted Newton iteration of a
    // force-driven step.
    if (D.linfty_norm() <= 1e-12 * U0.linfty_norm())
      return;
    try
      {
        callbacks.setup_jacobian(U0);
        VectorType F(owned, comm);
        elasticity.predictor_residual(U0, D, t_new, F);
        if (contact.active())
          {
            TimerOutput::Scope s(timer, "contact: residual");
            contact.assemble(U0, &F, nullptr);
          }
        F *= -1.;
        VectorType W(owned, comm);
        callbacks.solve_jacobian(F, W);
        W += U0;
        elasticity.constraints_at(t_new).distribute(W);
        // Keep the prediction only where it starts KINSOL closer to
        // equilibrium than U_trial does (KINSOL's scaled max-norm): at
        // the contact states where the projection changes piece (a
        // faceted master) the linearization at U0 can throw the
        // prediction far off, into inverted elements, for any load
        // increment however small.
        const auto scaled_norm = [&](const VectorType &u) {
          follow(u);
          try
            {
              VectorType R(owned, comm);
              callbacks.residual(u, R);
              R.scale(residual_scale);
              const double norm = R.linfty_norm();
              return std::isfinite(norm) ?
                       norm :
                       std::numeric_limits<double>::infinity();
            }
          catch (const InputError &)
            {
              throw;
            }
          catch (const std::exception &)
            {
              // An inverted element.
              return std::numeric_limits<double>::infinity();
            }
        };
        const double predicted = scaled_norm(W);
        if (predicted < std::numeric_limits<double>::infinity() &&
            predicted <= scaled_norm(U_trial))
          U_trial = W;
        else
          pcout << "  predictor not used (its residual is larger than "
                   "that of the last converged state with the new "
                   "prescribed values, or it inverts an element)"
                << std::endl;
      }
    catch (const InputError &)
      {
        throw;
      }
    catch (const std::exception &e)
      {
        pcout << "  predictor failed (" << e.what()
              << "); starting from the last converged state" << std::endl;
      }
  }

  template <int dim>
  NonlinearSolver::Result
  Problem<dim>::solve_step(VectorType &U_trial)
  {
    // Attempts at one step, each a KINSOL solve of a fixed problem with
    // the scene's strategy (full Newton steps in contact scenes); when
    // nodes alternate between two facets of a faceted master, the solve
    // stops there and goes on from that iterate with those nodes held on
    // one facet (at most three times), whatever the strategy; after any
    // other failure, or then, once with line search from the step's
    // initial guess if the scene asks for that retry. Every attempt's
    // iterations count.
    const VectorType U_start = U_trial;
    follow(U_trial);
    monitor.reset();
    stop_on_alternation = true;
    have_restart        = false;
    auto result =
      newton->solve(U_trial, callbacks, residual_scale, solution_scale);
    unsigned int attempts    = 1;
    bool         damped_done = false;
    bool         held        = false;
    while (!result.converged && !damped_done)
      {
        // Holding is a change of the problem, made between solves, and
        // reported in the log and the statistics (contact_<pair>_held).
        const auto holds = monitor.holds();
        const auto n_holds =
          Utilities::MPI::sum(static_cast<unsigned int>(holds.size()), comm);
        const bool again = n_holds > 0 && attempts < 4;
        const bool retry =
          again || scene.nonlinear_solver.retry_with_line_search;
        if (!retry)
          break;
        held = held || n_holds > 0;
        contact.hold(holds);
        pcout << "  step failed"
              << (attempts == 1 ? " with full Newton steps" : "") << ": "
              << result.message << std::endl;
        if (n_holds > 0)
          pcout << "  holding " << n_holds
                << " slave node(s) on one master facet (their projection "
                   "alternated between facets meeting at a corner)"
                << std::endl;
        pcout << (again ? "  retrying" : "  retrying with line search")
              << std::endl;
        // A solve stopped for alternating nodes goes on from where it was
        // (a new solve of the problem with the holds); any other failure
        // starts again from the step's initial guess.
        U_trial      = (again && have_restart) ? restart : U_start;
        have_restart = false;
        follow(U_trial);
        monitor.reset();
        // The last attempt runs to its end.
        stop_on_alternation =
          again &&
          (attempts + 1 < 4 || scene.nonlinear_solver.retry_with_line_search);
        const auto first = result;
        result           = (again ? newton : damped)
                   ->solve(U_trial, callbacks, residual_scale, solution_scale);
        result.iterations += first.iterations;
        result.linear_iterations += first.linear_iterations;
        ++attempts;
        damped_done = !again;
      }
    // A held node answers the held problem; where its gap to the facet's
    // plane is not its gap to the master (it has left the corner it
    // alternated at), that is not the scene's answer: the step fails and
    // is cut back instead.
    // Also where the step made no hold of its own: vertex holds carried
    // over from the last step (NodeToSurfaceFinite::commit_step()) hold
    // nodes that may have left their vertex since.
    if (result.converged && (held || contact.n_held() > 0))
      {
        std::ostringstream message;
        if (const double error = contact.held_gap_error(U_trial);
            error > max_held_gap_error)
          message << "the gap of a slave node held on one master facet "
                     "differs from its gap to the master by "
                  << error << " of the facet's length (at most "
                  << max_held_gap_error
                  << "): the held problem's answer is not the scene's";
        else if (const double effect = contact.held_force_effect(U_trial);
                 effect > max_held_force_effect)
          message << "the gaps of slave nodes held on one master facet "
                     "differ from their gaps to the master by enough to "
                     "move their nodal forces by up to "
                  << std::setprecision(2) << 100. * effect
                  << " % of their pair's largest (at most "
                  << 100. * max_held_force_effect
                  << " %; gap error times the contact stiffness E A / h): "
                     "the held problem's answer is not the scene's";
        if (!message.str().empty())
          {
            result.converged = false;
            result.message   = message.str();
          }
      }
    return result;
  }

  template <int dim>
  void
  Problem<dim>::postprocess(const unsigned int             step,
                            const double                   t_old,
                            const NonlinearSolver::Result &result,
                            const unsigned int             cut_backs,
                            const double                   wall_time)
  {
    const bool write_vtu =
      scene.output.write_vtu && (step % scene.output.every == 0 || t >= 1.);
    std::vector<std::pair<std::string, std::string>> row{
      {"step", std::to_string(step)},
      {"load_factor", format_number(t)},
      {"kinsol_iterations", std::to_string(result.iterations)},
      {"linear_iterations", std::to_string(result.linear_iterations)},
      {"residual", format_number(result.residual_norm)},
      {"cut_backs", std::to_string(cut_backs)},
      {"wall_time", format_number(wall_time)},
      {"dofs", std::to_string(elasticity.get_dof_handler().n_dofs())}};
    {
      TimerOutput::Scope s(timer, "postprocessing");
      const char        *axis[] = {"x", "y", "z"};
      // Contact forces at nodes with prescribed displacements go to their
      // supports: without them a slave node driven into its master (the
      // corner scene) left the reactions out of balance by its force.
      VectorType contact_forces;
      if (contact.active())
        {
          contact_forces.reinit(elasticity.locally_owned(), comm);
          contact.nodal_forces(U, contact_forces);
        }
      for (const auto &[surface, force] : elasticity.reactions(
             U, t, contact.active() ? &contact_forces : nullptr))
        for (unsigned int d = 0; d < dim; ++d)
          row.emplace_back("reaction_" + surface + "_" + axis[d],
                           format_number(force[d]));
      if (contact.active())
        {
          contact.commit_step(U, t_old, t);
          for (const auto &m : contact.take_messages())
            pcout << "  " << m << std::endl;
        }
      for (const auto &column : contact.statistics(U))
        row.push_back(column);
      if (contact.active()) // into the staging directory, see below
        {
          const auto  fields = contact.nodal_fields(U, t);
          std::string failure;
          // The contact VTU with the bodies' (every n-th step and the
          // last; until 2026-12-06 every step), the CSV every step.
          if (contact_output)
            failure = contact_output->write(fields, step, t, write_vtu);
          throw_output_error_on_any_process(failure, comm);
        }
      if (scene.manufactured_solution != "none")
        {
          const auto [l2, h1] = elasticity.errors(U);
          row.emplace_back("l2_error", format_number(l2));
          row.emplace_back("h1_error", format_number(h1));
        }
    }
    statistics->add_row(row);
    TimerOutput::Scope s(timer, "output");
    if (write_vtu)
      write_bodies(step);
    // The indexes (.pvd files, statistics.csv) after the data they list.
    output->commit_step([&]() {
      if (write_vtu)
        vtu->write_pvd();
      statistics->write();
    });
  }

  template <int dim>
  void
  Problem<dim>::write_bodies(const unsigned int step)
  {
    // The nodal contact forces on both sides of every pair (the
    // contact part of the residual, as a force on the bodies; zero
    // where a displacement is prescribed).
    VectorType contact_force;
    if (contact.active())
      {
        // All nodal contact forces, those at nodes with prescribed
        // displacements too (they were written as 0 there).
        contact_force.reinit(U);
        contact.nodal_forces(U, contact_force);
        contact_force *= -1.;
      }
    vtu->write(step, t, U, contact.active() ? &contact_force : nullptr);
    if (const auto n = vtu->inverted_points(); n > 0)
      pcout << "  warning: the stress fields of this step's VTU are NaN "
               "at "
            << n
            << " output point(s) where det F <= 0: vertices of strongly "
               "distorted cells, where the solution (det F > 0 at the "
               "quadrature points) inverts the cell. Refine the mesh "
               "there or use smaller load steps."
            << std::endl;
  }

  template <int dim>
  void
  Problem<dim>::run(const bool check_only)
  {
    Timer wall(comm);
    setup();
    print_summary();
    if (contact.active())
      {
        contact.set_time(0.);
        contact.check_initial_overclosure(U);
      }
    for (const auto &m : contact.take_messages())
      pcout << "  " << m << std::endl;
    if (check_only)
      {
        pcout << "glide: --check: the scene is set up and checked; nothing "
                 "was solved or written."
              << std::endl;
        return;
      }
    prepare_output();
    // From here a signal stops the run between load steps (the steps
    // written are complete); before, it ends the process at once.
    install_interrupt_handlers(Utilities::MPI::this_mpi_process(comm) == 0);

    LoadStepper stepper(scene.load_stepping);
    while (stepper.running())
      {
        throw_if_interrupted(comm); // SIGTERM: stop between steps
        const double t_old = stepper.time();
        t                  = stepper.begin_step();
        contact.set_time(t);
        contact.release_holds();
        pcout << "Step " << stepper.steps() + 1 << ": load factor " << t
              << " (increment " << t - t_old << ")" << std::endl;
        // The initial active set (Contact::close_touching_nodes()): at the
        // first contact of a pair, its nodes that touch the master start
        // closed, in the state the tangent predictor linearizes at (U_start)
        // and, after the prediction, in the state it predicts. Touching
        // nodes whose gap is round-off above 0 were otherwise open in the
        // prediction, and a displacement-driven patch test took 3
        // iterations instead of none (quadratic mortar facets).
        VectorType   U_start  = U;
        unsigned int n_closed = 0;
        if (contact.active())
          {
            follow(U_start);
            n_closed = contact.close_touching_nodes(U_start);
          }
        VectorType U_trial = U_start;
        elasticity.constraints_at(t).distribute(U_trial);
        Timer step_timer(comm);
        monitor.reset();
        if (scene.load_stepping.tangent_predictor)
          predict(U_start, t, U_trial);
        follow(U_trial);
        if (contact.active())
          n_closed = std::max(n_closed, contact.close_touching_nodes(U_trial));
        if (n_closed > 0)
          pcout << "  initial active set: " << n_closed
                << " slave node(s) within 1 % of their facet size of the "
                   "master start closed (their pair carried no force yet)"
                << std::endl;
        auto result = solve_step(U_trial);
        if (result.converged && contact.active())
          if (auto why = contact.passed_through(U, U_trial, t_old, t);
              !why.empty())
            {
              result.converged = false;
              result.message   = std::move(why);
            }
        if (!result.converged)
          {
            pcout << "  step failed: " << result.message << std::endl;
            try
              {
                stepper.reject(
                  result.message + elasticity.holding_hint() +
                  (corner_cycling ?
                     "\nNote: slave nodes cycled where the master surface "
                     "ends inside their slave facets (mortar): a sharp corner "
                     "of the master over a slave facet holds that facet "
                     "down, and as the corner crosses a slave node, the "
                     "node's constraint comes and goes, so smaller steps do "
                     "not help. Make the body with the corner the slave, or "
                     "use 'Formulation = node to surface' for this pair." :
                     ""));
              }
            catch (const std::runtime_error &)
              {
                // The run ends here: the last converged state, the one to
                // look at, goes into the VTU files if 'Every n steps' left
                // it out (until 2026-12-06 it was not written).
                if (scene.output.write_vtu && stepper.steps() > 0 &&
                    stepper.steps() % scene.output.every != 0)
                  {
                    t = stepper.time();
                    contact.set_time(t);
                    follow(U); // the failed attempts moved the search
                    try
                      {
                        TimerOutput::Scope s(timer, "output");
                        write_bodies(stepper.steps());
                        output->commit_step([&]() { vtu->write_pvd(); });
                        pcout << "  the bodies' VTU of step " << stepper.steps()
                              << " (load factor " << t
                              << "), the last that converged, is written "
                                 "for the diagnosis"
                              << std::endl;
                      }
                    catch (const OutputError &e)
                      {
                        // The step's failure is what the run reports.
                        pcout << "  the VTU of the last converged step "
                                 "could not be written: "
                              << e.what() << std::endl;
                      }
                  }
                throw;
              }
            t = t_old;
            pcout << "  cutting back: new increment " << stepper.increment()
                  << " (cut-back " << stepper.step_cut_backs() << " of at most "
                  << scene.load_stepping.maximum_cut_backs << ")" << std::endl;
            continue;
          }
        U = U_trial;
        stepper.accept();
        corner_cycling = false;
        pcout << "  converged in " << result.iterations
              << " iteration(s), scaled residual "
              << scientific(result.residual_norm) << std::endl;
        if (result.at_floor)
          pcout << "  Note: accepted above 'Nonlinear solver/Tolerance' = "
                << scene.nonlinear_solver.tolerance
                << (tolerance_factor < 1. ? " (x the loads' strain, above)" :
                                            "")
                << ": KINSOL could not reduce the residual further, and "
                << scientific(result.residual_norm)
                << " is within the round-off floor " << scientific(newton_floor)
                << " that "
                << (round_off_floor() > elasticity.round_off_floor() ?
                      "the contact gaps set (10 x machine epsilon x the "
                      "largest slave coordinate, over the slave facet "
                      "size: a contact zone far from the origin against "
                      "its facets)" :
                    elasticity.round_off_floor_from_loads() ?
                      "the loads set (10 x machine epsilon x the largest "
                      "nodal load over the softest Young's modulus and the "
                      "mean face area)" :
                      "the stiffest body sets (10 x machine epsilon x its "
                      "lambda + 2 mu / the softest Young's modulus)")
                << std::endl;
        postprocess(stepper.steps(),
                    t_old,
                    result,
                    stepper.cut_backs(),
                    step_timer.wall_time());
      }
    finish(stepper.steps(), stepper.cut_backs(), wall.wall_time());
  }

  template <int dim>
  void
  Problem<dim>::finish(const unsigned int steps,
                       const unsigned int cut_backs,
                       const double       wall_time)
  {
    timer.print_summary();
    const double memory      = peak_memory_mib(comm);
    const double per_process = peak_memory_mib(comm, true);
    pcout << "Finished " << steps << " load step(s) with " << cut_backs
          << " cut-back(s) in " << std::fixed << std::setprecision(2)
          << wall_time << " s; peak memory " << memory << " MiB";
    // Under MPI the sum over the processes (until 2026-12-06 not said).
    if (const unsigned int n = Utilities::MPI::n_mpi_processes(comm); n > 1)
      pcout << " (sum over " << n << " processes; largest process "
            << per_process << " MiB)";
    pcout << std::endl;
    std::string failure;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      try
        {
          output->write_file("timings.csv", [&](std::ostream &out) {
            out << "quantity,value\n"
                << "dofs," << elasticity.get_dof_handler().n_dofs() << "\n"
                << "processes," << Utilities::MPI::n_mpi_processes(comm) << "\n"
                << "linear_solver," << linear_solver.description() << "\n"
                << "total_wall_time," << wall_time << "\n"
                << "peak_memory_mib," << memory << "\n"
                << "peak_memory_per_process_mib," << per_process << "\n"
                << "contact_search_time," << contact.search_time() << "\n";
            for (const auto &[section, time] :
                 timer.get_summary_data(TimerOutput::total_wall_time))
              out << "time:" << section << "," << time << "\n";
            for (const auto &[section, n] :
                 timer.get_summary_data(TimerOutput::n_calls))
              out << "calls:" << section << "," << n << "\n";
          });
        }
      catch (const OutputError &e)
        {
          failure = e.what();
        }
    throw_output_error_on_any_process(failure, comm);
  }

  template <int dim>
  void
  run_scene(const Scene &scene, MPI_Comm comm, const bool check_only)
  {
    ConditionalOStream pcout(std::cout,
                             Utilities::MPI::this_mpi_process(comm) == 0);
    // An error (an input error found during set-up, a failed load step)
    // leaves the timer's scope before it is reported, so that the timer is
    // not destroyed while the exception is in flight (it would print a
    // warning about skipped MPI communication over the message).
    std::exception_ptr failure;
    {
      TimerOutput timer(comm,
                        pcout,
                        TimerOutput::never,
                        TimerOutput::wall_times);
      try
        {
          Problem<dim>(scene, comm, pcout, timer).run(check_only);
        }
      catch (...)
        {
          failure = std::current_exception();
        }
    }
    if (failure)
      std::rethrow_exception(failure);
  }

  template void
  run_scene<2>(const Scene &, MPI_Comm, bool);
  template void
  run_scene<3>(const Scene &, MPI_Comm, bool);
  template class Problem<2>;
  template class Problem<3>;
} // namespace glide
