#pragma once

#include <glide/contact/active_set_monitor.h>
#include <glide/contact/enforcement.h>
#include <glide/contact/formulation.h>
#include <glide/contact/small_sliding.h>
#include <glide/mechanics/elasticity.h>
#include <glide/output/contact_output.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <memory>
#include <string>
#include <vector>

namespace glide
{
  /**
   * The contact part (DESIGN.md, "The contact part, second generation"):
   * every contact pair of the scene, each with its formulation (chosen by
   * name: node to surface with finite or small sliding, surface to surface
   * with small sliding; formulation.h) and its enforcement (hard or
   * penalty; enforcement.h). It depends on the bodies only through a narrow
   * interface: reference positions and DoF indices of slave nodes, and the
   * current iterate U.
   *
   * Hard contact adds a block of multipliers per slave node (the normal
   * contact force lambda >= 0), numbered after the displacement DoFs, with
   * the complementarity function C(lambda, g) = lambda - max(0, lambda - c
   * g) = 0; c = E_pair A_s / h_s makes c g a force, so rows and iteration
   * counts do not depend on units. The active set is read off the current
   * iterate inside the residual: Newton on (u, lambda) is the primal-dual
   * active set method, driven by KINSOL. The residual is a function of the
   * iterate, the load factor, the holds of the current attempt and the
   * history committed after the last converged step (commit_step()), and
   * of nothing else (R16.1).
   */
  template <int dim>
  class Contact
  {
  public:
    Contact(const Scene           &scene,
            const Elasticity<dim> &elasticity,
            MPI_Comm               comm);

    /// The formulations log through this object: it stays where it is.
    Contact(const Contact &) = delete;
    Contact &
    operator=(const Contact &) = delete;

    /// Find the slave nodes of every pair and number the multipliers from
    /// @p first_multiplier on (MPI: each process numbers its own nodes).
    void
    setup(const dealii::types::global_dof_index first_multiplier);

    /// True if the scene has contact pairs.
    bool
    active() const
    {
      return !pairs.empty();
    }

    /// Multiplier indices owned by this process.
    const dealii::IndexSet &
    owned_multipliers() const
    {
      return multipliers;
    }

    dealii::types::global_dof_index
    n_multipliers() const
    {
      return total_multipliers;
    }

    /// The DoFs this process reads besides its own (under MPI: the nodes
    /// of master surfaces and mortar slave facets of other processes):
    /// their rows are in the sparsity pattern and their constraints must
    /// be known here (Elasticity::setup_system()).
    const dealii::IndexSet &
    ghost_dofs() const
    {
      return read_ghosts;
    }

    /// The scaled residual that round-off in the gaps alone leaves in the
    /// contact rows (collective): a gap is the difference of positions, so
    /// it carries a few machine epsilon times their magnitude, and a
    /// closed node's row is c g. Large where the contact zone lies far
    /// from the origin against its facets; see Elasticity::round_off_floor().
    double
    round_off_floor() const;

    /// The largest distance an analytical rigid master's points next to
    /// the slave nodes move from load factor 0 to any of @p factors
    /// (collective; 0 without a moving analytical master): what a moving
    /// master can press into the bodies, for the tolerance of tiny loads
    /// (Problem's set-up, Elasticity::driving_strain()).
    double
    largest_master_motion(const std::vector<double> &factors) const;

    /// Couplings of contact terms, for the sparsity pattern: each slave
    /// node with the master nodes it can reach by sliding about one master
    /// facet from where it is now.
    void
    add_sparsity(dealii::DynamicSparsityPattern &dsp);

    /// True if a slave node at iterate @p U projects onto master nodes
    /// outside the current sparsity pattern (it slid further than
    /// add_sparsity() allowed for), or follow() gathered master facets
    /// again: then the pattern must be rebuilt.
    bool
    needs_new_pattern(const VectorType &U);

    /// Under MPI (R15.2; collective): each process holds the master facets
    /// within reach of its slave nodes, gathered where they were. Where
    /// the slave nodes and the master of a finite-sliding pair have moved
    /// by more than half of gather_margin since, gather them again around
    /// the positions at @p U. True if it did: the ghost DoFs and the
    /// sparsity pattern must then be rebuilt (Problem::rebuild_pattern()).
    bool
    follow(const VectorType &U);

    /// The state of every locally owned slave node (all pairs, in order)
    /// at iterate @p U, for the driver's ActiveSetMonitor. Reads nothing
    /// but U and the committed state.
    std::vector<typename ActiveSetMonitor<dim>::Status>
    status(const VectorType &U) const;

    /// Hold the slave nodes @p holds (indices as in status(), with their
    /// pieces) on one facet of a faceted master, or at the vertex between
    /// the two facets they alternated between, for the next solves of this
    /// step (Formulation::hold()). Chosen by the
    /// driver between two attempts at a step, never inside one, so that
    /// the residual stays a function of the iterate within each solve.
    void
    hold(const std::vector<Hold> &holds);

    /// End all holds (at the start of every step).
    void
    release_holds();

    /// At iterate @p U, the largest difference between a held node's gap
    /// (to the plane of the facet it is held on) and its gap to the master
    /// (the free projection's), relative to that facet's length (all pairs
    /// and processes; 0 without holds).
    double
    held_gap_error(const VectorType &U) const;

    /// Number of held slave nodes of all pairs and processes (collective).
    unsigned int
    n_held() const;

    /// At iterate @p U, the largest held_force_effect() of any pair: how
    /// far the held nodes' gap errors may move their nodal forces,
    /// relative to their pair's largest (0 without holds).
    double
    held_force_effect(const VectorType &U) const;

    /// Scale the stabilization of stabilization_weight(): 1 (the default)
    /// in full, 0 off (to compare the Jacobian with finite differences),
    /// in between while Newton converges (Problem: the residual reduction
    /// of the solve once the active set has settled).
    void
    set_jacobian_stabilization(const double factor)
    {
      stabilize = factor;
    }


    /// Move rigid masters to load factor @p t.
    void
    set_time(const double t);

    /**
     * The multipliers of hard contact with the DoFs of their slave nodes,
     * for MultiplierCondensation, or none, with the reason in @p why_not,
     * where they cannot be eliminated: a formulation that spreads a force
     * over several slave nodes (surface to surface, small sliding), a slave
     * node at a hanging node (tied to its neighbours), a node that is slave
     * of two pairs or also on a master surface. Collective: this process's
     * multipliers; the reason found first in rank order on every process.
     */
    std::vector<std::pair<dealii::types::global_dof_index,
                          std::vector<dealii::types::global_dof_index>>>
    condensable_multipliers(std::string &why_not) const;

    /// Add the contact terms to F (and to J if given), condensed with the
    /// displacement constraints. Changes nothing: F is a function of U,
    /// the load factor, the holds and the committed state (R16.1).
    void
    assemble(const VectorType &U, VectorType *F, MatrixType *J) const
    {
      assemble(U, F, J, elasticity.update_constraints());
    }

    /// Add the contact forces at U to F, condensed with the hanging-node
    /// constraints only: at a DoF with a prescribed displacement F then
    /// holds the contact force that its support carries too (reactions).
    void
    nodal_forces(const VectorType &U, VectorType &F) const
    {
      assemble(U, &F, nullptr, elasticity.hanging_constraints());
    }

    /// Entries of KINSOL's scaling vectors for the multiplier rows and
    /// unknowns (contact forces): 1 / (E_pair A_ref), E_pair the pair's
    /// contact modulus (see contact_modulus()).
    void
    set_scaling(VectorType &residual_scale, VectorType &solution_scale) const;

    /// Per pair: active nodes, total normal contact force, largest
    /// penetration; as statistics columns.
    std::vector<std::pair<std::string, std::string>>
    statistics(const VectorType &U) const;

    /**
     * Collective: why the converged step from @p U_old at load factor
     * @p t_old to @p U_new at @p t_new is not the scene's answer, or empty.
     * A rigid circle, cylinder or sphere that passed through slave nodes
     * within the increment leaves them open at both ends, with no force
     * and no warning: a node whose straight path relative to the master
     * goes deeper into it than its slave facet size (a node sliding round
     * the master at a small gap dips in by the sagitta of its path only)
     * makes the step fail, and the load stepper cuts it back
     * (RigidMaster::passage_depth()). Masters that are meshed surfaces are
     * not checked.
     */
    std::string
    passed_through(const VectorType &U_old,
                   const VectorType &U_new,
                   const double      t_old,
                   const double      t_new) const;

    /// After a converged step from load factor @p t_old to @p t_new:
    /// store each formulation's history (positions, projections, offsets)
    /// and accumulate the slip CSLIP of every closed slave node (R12.1);
    /// log failed projections, held nodes and nodes that slid too far.
    void
    commit_step(const VectorType &U, const double t_old, const double t_new);

    /**
     * The initial active set of a load step (hard contact): for a pair that
     * carries no force at the step's initial guess @p U (every multiplier
     * zero: its first contact), close the slave
     * nodes that touch the master already, those with g <= 0.01 h (h
     * the node's facet size), by setting their multiplier just above c g,
     * where the complementarity function switches to its closed branch.
     * A body held only by contact (a cylinder pressed onto a block by a
     * force) otherwise starts with every node open wherever no node sits
     * exactly on the master, as with mortar's weighted gaps (an average of
     * g over the node's facets, positive at the first contact point of two
     * curved surfaces) or a slave node between two nodes of a faceted
     * master: its Jacobian is singular, the first Newton step (resisted
     * only by the Jacobian stabilization) throws the body far into the
     * other, and the active set cycles. With mortar, the node at the first
     * contact point is closed (the dual basis makes its weighted gap
     * slightly negative there) but carries the body alone in the first
     * iteration, which sinks into the other as if under a point load
     * (measured on parameters/hertz-2d-elastic.prm, block slave: 19
     * iterations with a line-search retry, 5 with this). The weighted gap of
     * the nodes next to the first contact point of two surfaces with relative
     * curvature kappa is about kappa h^2 / 6, so 1 % of h covers them on any
     * mesh that resolves the curvature (kappa h <= 0.06). It changes the
     * starting point only, never the residual (R16.1); nodes closed wrongly
     * open in the next iteration. Returns the number of nodes closed (all
     * processes).
     */
    unsigned int
    close_touching_nodes(VectorType &U) const;

    /**
     * Warn (take_messages()) about every pair whose slave nodes start, at
     * iterate @p U (the initial state), inside the master by more than their
     * facet size: a misplaced mesh or a wrong 'Slave inside' gives no other
     * sign, and the first load step pushes such nodes out at once with a
     * large force. An interference fit (a fraction of the facet size) is
     * not reported. Returns the number of such nodes (all processes).
     */
    unsigned int
    check_initial_overclosure(const VectorType &U);

    /// The contact fields of every pair's slave nodes at iterate @p U and
    /// load factor @p t (COPEN, force, CPRESS, CSTATUS, CSLIP, normal,
    /// tangents), gathered on the first process, for the ContactWriter.
    std::vector<ContactPairFields<dim>>
    nodal_fields(const VectorType &U, const double t);

    /// Wall time spent in the search for deformable masters (R-tree set-up
    /// and projections, in residuals, Jacobians and pattern checks), in
    /// seconds: the search share of the run.
    double
    search_time() const;

    /// Effects for the log.
    std::vector<std::string>
    active_effects() const;

    /// Notes and warnings for the log since the last call (slave nodes
    /// without an anchor after setup(), R7.4; nodes that slid further than
    /// small sliding allows after commit_step(), R12.2); empty on all but
    /// the first process.
    std::vector<std::string>
    take_messages();

    /// Small-sliding anchors of pair @p pair's locally owned slave nodes
    /// (for tests).
    const std::vector<typename SmallSliding<dim>::Anchor> &
    anchors(const unsigned int pair) const;

    /// The formulation of pair @p pair (for tests).
    const Formulation<dim> &
    formulation_of(const unsigned int pair) const
    {
      return *pairs[pair].formulation;
    }

    /// The locally owned slave nodes of pair @p pair (for tests).
    const std::vector<SlaveNode<dim>> &
    slave_nodes(const unsigned int pair) const
    {
      return pairs[pair].nodes;
    }

  private:
    /// assemble() with the given constraints.
    void
    assemble(const VectorType                        &U,
             VectorType                              *F,
             MatrixType                              *J,
             const dealii::AffineConstraints<double> &constraints) const;

    struct Pair
    {
      const ContactPairParameters *parameters;
      /// The modulus that sets the contact stiffness of the pair: the
      /// smaller of the slave's and the master's Young's moduli (a rigid
      /// master counts as infinitely stiff), see setup().
      double modulus = 0.;
      /// A deformable master less than quadratic_master_ratio times stiffer
      /// than the slave: the slave nodes' point forces deform it.
      bool compliant_master = false;
      /// The log has said that the master's facets are the shorter where
      /// the slave nodes touch (finer_master_facets(); once per run).
      bool finer_master_said = false;
      /// The log has named the slave nodes that a boundary condition holds
      /// along the contact normal (mark_prescribed(); once per run).
      bool prescribed_said = false;
      /// The log has said that slave nodes penetrate the master beyond
      /// what their averaged constraints show (hidden_penetration(); once
      /// per run).
      bool hidden_said = false;
      /// Under MPI (R15.2): how far slave nodes and master may move (the
      /// largest motion of each, summed) from where the master facets
      /// were gathered before a search could reach facets not held here
      /// (finite sliding; 0: gathered once), how far beyond that a search
      /// reaches, and the slave nodes' displacements at the gather.
      double                                   gather_margin = 0.;
      double                                   gather_reach  = 0.;
      std::vector<double>                      gathered_at;
      unsigned int                             gathers = 0;
      std::vector<SlaveNode<dim>>              nodes; ///< locally owned
      std::unique_ptr<Formulation<dim>>        formulation;
      std::unique_ptr<ContactEnforcement<dim>> enforcement;
    };

    /// Hanging slave nodes (a locally refined slave surface) into the
    /// slave nodes they are constrained to (find_slave_nodes()): one whose
    /// DoFs are a weighted mean of other slave nodes' (u_h = sum w_p u_p;
    /// quadratic elements: equal to one node's) gives them its tributary
    /// area, normal and surface mass with those weights
    /// (SlaveNode::hanging) and is no constraint point itself.
    void
    condense_hanging_nodes(
      std::map<dealii::types::global_dof_index, SlaveNode<dim>> &found,
      std::map<dealii::types::global_dof_index, unsigned int> &n_facets) const;

    /// Slave nodes of pair @p p (parameters) with their areas, sizes and
    /// normals, locally owned ones only; @p slave_modulus gets the smallest
    /// Young's modulus of the slave bodies.
    std::vector<SlaveNode<dim>>
    find_slave_nodes(const ContactPairParameters &p,
                     const std::string           &path,
                     bool                        &node_based,
                     double                      &slave_modulus) const;

    /// The force and status of every constraint of @p pair at iterate @p U
    /// (the formulation must have been moved to U).
    std::vector<typename ContactEnforcement<dim>::Force>
    forces(const Pair                         &pair,
           const std::vector<Constraint<dim>> &s,
           const VectorType                   &U) const;

    /**
     * Whether a boundary condition prescribes the motion of the constraint
     * @p s of @p node along its force direction: every DoF on which the
     * force l.force acts with a share above 1e-6 of its norm carries a
     * Dirichlet condition (a slave node fixed or held by YSYMM against a
     * rigid plane with normal y). The constraint's multiplier row has no
     * free column then and the Newton systems are singular: such a
     * constraint is taken out (Outcome::prescribed, open, lambda = 0) and
     * the condition's reaction carries the node's share of the contact
     * force. Decided from U and the conditions alone, in the residual
     * and the Jacobian alike (R16.1). Only a node with a prescribed DoF of
     * its own can be prescribed (its own share of the force is its normal
     * times its weight), so the others skip the linearization.
     */
    bool
    has_prescribed_dof(const SlaveNode<dim> &node) const;
    void
    mark_prescribed(Constraint<dim>                                &s,
                    const typename Formulation<dim>::Linearization &l) const;

    /// The constraints of every node of @p pair at iterate @p U (moves the
    /// formulation to U; Outcome::prescribed marked).
    std::vector<Constraint<dim>>
    constraints(const Pair &pair, const VectorType &U) const;

    /// @p U with the entries of ghost_dofs() (U itself on one process):
    /// what every function that takes an iterate reads.
    const VectorType &
    view(const VectorType &U) const;

    /// The DoFs the formulations read (ghost_dofs()), again.
    void
    update_read_ghosts();

    /// Boxes around this process's slave nodes of @p pair at @p U (the
    /// view(); empty: the reference positions), grown by gather_margin +
    /// gather_reach (covering_boxes()): the master facets it needs; none
    /// where it has no slave nodes.
    std::vector<dealii::BoundingBox<dim>>
    slave_region(const Pair &pair, const VectorType &U) const;

    /// Collective: the largest motion of a slave node of @p pair plus that
    /// of a master node since the master facets were gathered (U: view()).
    double
    motion_since_gather(const Pair &pair, const VectorType &U) const;

    /// Add a log message listing @p nodes (gathered from all processes).
    void
    report(const std::vector<std::string> &nodes,
           const std::string              &before,
           const std::string              &after);

    /**
     * Stiffness added to the Jacobian (never to the residual) for an open
     * slave node closer to the master than its facet size h:
     *   K += s_J c (1 - g/h)^2 dg/du (dg/du)^T,
     * with c the node's NCP constant (E A / h). A body held only by contact
     * (a cylinder pressed by a force onto a block, touching at one node)
     * has rigid motions that no closed node resists yet: its Jacobian is
     * singular, the direct solver fails or returns an arbitrary rotation,
     * and the active set cycles. The springs of the nodes about to touch
     * remove those motions from the Newton step. The residual, and hence
     * the converged solution, is that of the unmodified problem; the
     * Newton step is inexact only in the rows of open nodes near the
     * master. The driver applies it in full while the active set changes
     * and, once it has settled, scaled by the square of the residual's
     * reduction in the solve (set_jacobian_stabilization()). The
     * Jacobian's error then shrinks faster than the residual, and the last
     * iterations converge quadratically (with it always in full, the error
     * shrank by only about 1/500 per iteration at the end). A rigid motion
     * that only the springs resist never leaves the Jacobian singular
     * (switched off, it did: a cylinder touching a block at one node
     * turned by an arbitrary angle in the next step).
     */
    double
    stabilization_weight(
      const SlaveNode<dim>                          &node,
      const Constraint<dim>                         &s,
      const typename ContactEnforcement<dim>::Force &f) const;

    /// The factor s_J of stabilization_weight(): small enough that the
    /// error contraction per iteration at open nodes, about s_J / (1 +
    /// s_J), is far below Newton's, large enough that a free rigid motion
    /// is resisted like a spring of 1/1000 of the contact stiffness.
    static constexpr double stabilization = 1e-3;
    /// Slave modulus over master modulus from which the set-up warns that
    /// the roles should be swapped.
    static constexpr double stiff_slave_ratio = 10.;
    /// Master modulus over slave modulus below which node to surface with
    /// quadratic elements warns that its nodal pressure zigzags.
    static constexpr double quadratic_master_ratio = 100.;
    /// Slave facet length over master facet length at the closed slave
    /// nodes (median) from which finer_master_facets() warns.
    static constexpr double finer_master_ratio = 2.;

    /// After a converged step: warn (once per pair) where the closed slave
    /// nodes of a node-to-surface pair with a compliant master touch master
    /// facets that are finer_master_ratio or more times shorter than their
    /// own, in the median over the contact area (doc/theory/node-to-surface.md,
    /// "Quadratic elements between two deformable bodies": the master deforms
    /// under the slave nodes' point forces, and the nodal pressure zigzags).
    /// After a converged step (once per run): warn where a translation
    /// of a body that only contact holds (Elasticity::free_motions()) is
    /// perpendicular to the reference normal and to the force direction of
    /// every closed slave node on it or against it: frictionless contact
    /// transmits no force along it, so the solution is not unique in it
    /// (two blocks stacked flat, the upper one free in x: its slip was
    /// whatever the linear solver picked, and differed between 1 and 3
    /// processes). @p closed: the closed slave nodes of each pair, with
    /// their constraints' normals.
    void
    unheld_motions(
      const std::vector<
        std::vector<std::pair<unsigned int, dealii::Tensor<1, dim>>>> &closed);

    /// The held nodes' estimated effect on their nodal forces (R16.1: a
    /// heuristic that changes the problem is reported with its effect on
    /// the answer): the largest gap error of a held node (to its facet's
    /// plane instead of the master) times its contact stiffness E A / h
    /// (in series with the penalty stiffness), relative to the pair's
    /// largest nodal force (collective; 0 without holds).
    double
    held_force_effect(
      const Pair                                                 &pair,
      const std::vector<Constraint<dim>>                         &s,
      const std::vector<typename ContactEnforcement<dim>::Force> &f) const;

    void
    finer_master_facets(Pair                               &pair,
                        const std::vector<Constraint<dim>> &s,
                        const std::vector<bool>            &closed);

    /// After a converged step: warn (once per pair) where a slave node
    /// penetrates the master by more than hidden_penetration_ratio of its
    /// facet size (a thousandth where no constraint of the pair is
    /// @p closed: it carries no force) beyond what its constraint's gap,
    /// averaged over a region (surface to surface), shows
    /// (doc/theory/small-sliding.md: coarse slave facets on a curved master
    /// hide penetration, and contact that has begun).
    void
    hidden_penetration(Pair                               &pair,
                       const std::vector<Constraint<dim>> &s,
                       const std::vector<bool>            &closed);

    /// Penetration of a slave node, relative to its facet size, that its
    /// averaged constraint does not show, beyond which the log warns.
    static constexpr double hidden_penetration_ratio = 0.05;

    double stabilize = 1.;

    const Scene           &scene;
    const Elasticity<dim> &elasticity;
    MPI_Comm               comm;
    std::vector<Pair>      pairs;
    /// The iterate of the last needs_new_pattern() that asked for a new
    /// pattern (empty before): add_sparsity() couples at it.
    VectorType               last_displacement;
    double                   time = 0.; ///< load factor
    std::vector<std::string> messages;
    /// unheld_motions() has warned (or found no free translation).
    bool unheld_said = false;
    /// Elasticity::free_motions(), for unheld_motions().
    std::vector<std::vector<typename Elasticity<dim>::FreeMotion>> free_motions;
    bool             free_motions_found = false;
    dealii::IndexSet multipliers;
    dealii::IndexSet read_ghosts;
    bool             import_ghosts = false;
    /// read_ghosts changed (follow()): view() sets up ghosted again.
    mutable bool ghosts_changed = false;
    /// follow() gathered since the last needs_new_pattern().
    bool                            gathered = false;
    mutable VectorType              ghosted;
    dealii::types::global_dof_index total_multipliers  = 0;
    double                          max_youngs_modulus = 0.;
  };
} // namespace glide
