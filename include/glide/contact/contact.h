#pragma once

#include <glide/contact/active_set_monitor.h>
#include <glide/contact/master_surface.h>
#include <glide/contact/rigid_master.h>
#include <glide/contact/small_sliding.h>
#include <glide/mechanics/elasticity.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace glide
{
  /**
   * The contact part (DESIGN.md, "Contact formulation"): every contact pair
   * of the scene, node-to-surface, finite sliding, against analytical rigid
   * masters, with hard or penalty enforcement (P2.1, P2.3, P1.4). It
   * depends on the bodies only through a narrow interface: reference
   * positions and DoF indices of slave nodes, and the current iterate U.
   *
   * Hard contact adds one unknown per slave node, the normal contact force
   * lambda (>= 0), numbered after the displacement DoFs. Its equation is the
   * complementarity function
   *   C(lambda, g) = lambda - max(0, lambda - c g) = 0,
   * which holds exactly when lambda >= 0, g >= 0, lambda g = 0; c = E_pair
   * A_s / h_s (A_s the slave node's tributary area, h_s its facet size) makes
   * c g a force, so rows and iteration counts do not depend on units. The
   * active set is read off the current iterate inside the residual: Newton
   * on (u, lambda) is the primal-dual active set method, driven by KINSOL.
   * The displacement rows get -lambda dg/du; their Jacobian includes the
   * curvature term -lambda d2g/du2 of curved masters.
   */
  template <int dim>
  class Contact
  {
  public:
    Contact(const Scene           &scene,
            const Elasticity<dim> &elasticity,
            MPI_Comm               comm);

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

    /// Couplings of contact terms, for the sparsity pattern: each slave
    /// node with the master nodes it can reach by sliding about one master
    /// facet from where it is now.
    void
    add_sparsity(dealii::DynamicSparsityPattern &dsp);

    /// True if a slave node at iterate @p U projects onto master nodes
    /// outside the current sparsity pattern (it slid further than
    /// add_sparsity() allowed for): then the pattern must be rebuilt.
    bool
    needs_new_pattern(const VectorType &U);

    /// The state of every locally owned slave node (all pairs, in order)
    /// at iterate @p U, for the driver's ActiveSetMonitor. Reads nothing
    /// but U and the committed state.
    std::vector<typename ActiveSetMonitor<dim>::Status>
    status(const VectorType &U) const;

    /// Hold the slave nodes @p holds (indices as in status(), with their
    /// piece) on one facet of a faceted master for the next solves of this
    /// step: their gap is measured to that facet's plane. Chosen by the
    /// driver between two attempts at a step, never inside one, so that
    /// the residual stays a function of the iterate within each solve.
    void
    hold(const std::vector<std::pair<unsigned int, int>> &holds);

    /// End all holds (at the start of every step).
    void
    release_holds();

    /// Turn the stabilization of stabilization_weight() on (the default)
    /// or off (to compare the Jacobian with finite differences).
    void
    set_jacobian_stabilization(const bool on)
    {
      stabilize = on;
    }


    /// Move rigid masters to load factor @p t.
    void
    set_time(const double t);

    /// Add the contact terms to F (and to J if given), condensed with the
    /// displacement constraints. Changes nothing: F is a function of U,
    /// the load factor, the holds and the committed state (R16.1).
    void
    assemble(const VectorType &U, VectorType *F, MatrixType *J) const;

    /// Entries of KINSOL's scaling vectors for the multiplier rows and
    /// unknowns (contact forces): 1 / (E_pair A_ref), E_pair the pair's
    /// contact modulus (see contact_modulus()).
    void
    set_scaling(VectorType &residual_scale, VectorType &solution_scale) const;

    /// Per pair: active nodes, total normal contact force, largest
    /// penetration; as statistics columns.
    std::vector<std::pair<std::string, std::string>>
    statistics(const VectorType &U) const;

    /// After a converged step from load factor @p t_old to @p t_new:
    /// accumulate the slip CSLIP of every closed slave node, the tangential
    /// part of its motion relative to the master's material point under it
    /// (R12.1 for finite sliding).
    void
    update_slip(const VectorType &U, const double t_old, const double t_new);

    /// Write, for step @p step at load factor @p time, one CSV row per
    /// slave node (positions, COPEN, force, CPRESS, CSTATUS, CSLIP) and, if
    /// @p vtu, a VTU point set with the same fields, the contact normal and
    /// the displacement, listed in `contact-<pair>.pvd` for ParaView.
    void
    write_nodes(const VectorType  &U,
                const std::string &directory,
                const unsigned int step,
                const double       time,
                const bool         vtu);

    /// Wall time spent in the search for deformable masters (R-tree set-up
    /// and projections, in residuals, Jacobians and pattern checks), in
    /// seconds: the search share of the run.
    double
    search_time() const
    {
      return searching.count();
    }

    /// Effects for the log.
    std::vector<std::string>
    active_effects() const;

    /// Notes and warnings for the log since the last call (slave nodes
    /// without an anchor after setup(), R7.4; nodes that slid further than
    /// small sliding allows after update_slip(), R12.2); empty on all but
    /// the first process.
    std::vector<std::string>
    take_messages();

    /// Small-sliding anchors of pair @p pair's locally owned slave nodes
    /// (for tests).
    const std::vector<typename SmallSliding<dim>::Anchor> &
    anchors(const unsigned int pair) const
    {
      return pairs[pair].anchors;
    }

  private:
    struct SlaveNode
    {
      dealii::Point<dim>                               X;
      std::array<dealii::types::global_dof_index, dim> dofs;
      double                          area = 0.; ///< tributary area
      double                          size = 0.; ///< facet size
      dealii::types::global_dof_index multiplier =
        dealii::numbers::invalid_dof_index;
      double c = 0.; ///< NCP constant E_pair A / h
      double k = 0.; ///< penalty stiffness * area
      /// Surface slaves: area-weighted outward normal, and int N_a N_b dA
      /// with the neighbours b on the slave surface (keyed by x DoF).
      dealii::Tensor<1, dim>                            normal;
      std::map<dealii::types::global_dof_index, double> mass;
    };
    struct Pair
    {
      const ContactPairParameters *parameters;
      /// The modulus that sets the contact stiffness of the pair: the
      /// smaller of the slave's and the master's Young's moduli (a rigid
      /// master counts as infinitely stiff), see setup().
      double                              modulus = 0.;
      std::unique_ptr<RigidMaster<dim>>   master;  ///< analytical rigid
      std::unique_ptr<MasterSurface<dim>> surface; ///< deformable body
      /// Small sliding (R6): the anchors and tangent planes, per node (for
      /// analytical rigid masters only X0 and N0 are used).
      bool                                            small = false;
      std::unique_ptr<SmallSliding<dim>>              planes;
      std::vector<typename SmallSliding<dim>::Anchor> anchors;
      /// Tangential coordinates of the slave node relative to its anchor at
      /// the end of the last converged step (along the plane's tangents).
      std::vector<std::array<double, 2>> previous_offset;
      std::vector<bool>                  warned;
      /// Per node: master nodes coupled in the sparsity pattern (sorted),
      /// and the projection at the end of the last converged step.
      std::vector<std::vector<unsigned int>>               coupled;
      std::vector<typename MasterSurface<dim>::Projection> previous_projection;
      std::vector<SlaveNode> nodes; ///< locally owned nodes
      /// Per node: position at the end of the last converged step, and
      /// accumulated slip.
      std::vector<dealii::Point<dim>> previous_position;
      std::vector<double>             slip;
      /// Accumulated slip components along the local tangent directions
      /// (CSLIP1, CSLIP2; only the first in 2D).
      std::vector<std::array<double, 2>> slip_components;
      /// Deformable faceted masters: per node, the piece it is held on
      /// (-1: none), set by hold() between two attempts at a step. At a
      /// faceted corner the force direction jumps between the facets'
      /// normals, and Newton can alternate between them forever (f = 0
      /// only: a smoothed master has no corners). The holds end with the
      /// step. Carrying
      /// those still within 2 % of a facet of their piece into the next
      /// step was tried: the faceted ironing die's press took 10 instead of
      /// 39 cut-backs, but the full ironing run then stopped at load factor
      /// 0.785 (it finishes without). Holding on without such a band let
      /// the held nodes accumulate: the 2D Hertz peak pressure with f = 0
      /// went from 2 % to 12 % too high, and the ironing die's nodes ended
      /// up 1.7 past their facets.
      std::vector<int> held_piece;
      /// Deformable masters: per node, the last projection with the slave
      /// position, master version() and held piece it was computed for
      /// (the residual and the Jacobian of one iterate share it).
      struct CachedProjection
      {
        typename MasterSurface<dim>::Projection projection;
        dealii::Point<dim>                      x;
        std::uint64_t version = std::numeric_limits<std::uint64_t>::max();
        int           held    = -1;
      };
      mutable std::vector<CachedProjection> cached;
      /// Written steps, for the .pvd file.
      std::vector<std::pair<double, std::string>> records;
    };
    struct NodeState
    {
      dealii::Point<dim>     x;
      double                 gap = 0.;
      dealii::Tensor<1, dim> normal;
      /// False where a slave node projects beyond the end of a deformable
      /// master (then it is open, with gap +infinity).
      bool                                    found = true;
      typename RigidMaster<dim>::Projection   rigid;
      typename MasterSurface<dim>::Projection projection;
      dealii::Point<dim> anchor; ///< small sliding: current anchor point
      /// The constraint's slave point: the node, or (surface to surface)
      /// the weighted centre of its averaging region.
      dealii::Point<dim> point;
      /// Local tangent directions (R13.1).
      std::array<dealii::Tensor<1, dim>, dim - 1> tangents;
      double                                      lambda = 0.; ///< normal force
      bool                                        closed = false;
    };
    /// State of a slave node at iterate U (deformable masters must have
    /// been moved to U with set_displacement()).
    NodeState
    state(const Pair &pair, const SlaveNode &node, const VectorType &U) const;

    /// Gap and force direction with their derivatives at state @p s of
    /// iterate @p U.
    void
    linearize(const Pair                                 &pair,
              const SlaveNode                            &node,
              const NodeState                            &s,
              const VectorType                           &U,
              typename MasterSurface<dim>::Linearization &l) const;

    /// Displacement component @p i at the iterate of the last
    /// needs_new_pattern() that asked for a new pattern (0 before).
    double
    current_displacement(const dealii::types::global_dof_index i) const;

    /// Anchors and tangent planes of a small-sliding pair (R6-R8).
    void
    setup_small_sliding(Pair &pair, const std::string &path);

    /// Small-sliding anchor on an analytical rigid master: the closest
    /// point of @p X and the master normal there (initial position).
    typename SmallSliding<dim>::Anchor
    rigid_anchor(const Pair &pair, const dealii::Point<dim> &X) const;

    /// Surface-to-surface anchor on an analytical rigid master (R9.2 with
    /// the closest points as the landing points).
    typename SmallSliding<dim>::Anchor
    rigid_anchor_sts(const Pair                            &pair,
                     const std::vector<dealii::Point<dim>> &X,
                     const std::vector<double>             &phi,
                     const dealii::Tensor<1, dim>          &slave_normal,
                     const std::array<bool, dim>           &symmetric,
                     typename SmallSliding<dim>::Fallback  &reason) const;

    /// Surface-to-surface anchors of a small-sliding pair (R9), with the
    /// fall-back to node to surface counted in the log (R9.4).
    void
    setup_surface_to_surface(Pair &pair);

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
     * master. The driver applies it only while the active set changes
     * (set_jacobian_stabilization()), so that the last iterations, with
     * the active set settled, are exact Newton steps and converge
     * quadratically (with it always on, the error shrank by only about
     * 1/500 per iteration at the end).
     */
    double
    stabilization_weight(const Pair      &pair,
                         const SlaveNode &node,
                         const NodeState &s) const;

    /// The factor s_J of stabilization_weight(): small enough that the
    /// error contraction per iteration at open nodes, about s_J / (1 +
    /// s_J), is far below Newton's, large enough that a free rigid motion
    /// is resisted like a spring of 1/1000 of the contact stiffness.
    static constexpr double stabilization = 1e-3;
    bool                    stabilize     = true;

    /// Move the deformable masters to iterate @p U.
    void
    move_surfaces(const VectorType &U) const;

    const Scene                          &scene;
    const Elasticity<dim>                &elasticity;
    MPI_Comm                              comm;
    std::vector<Pair>                     pairs;
    VectorType                            last_displacement;
    mutable std::chrono::duration<double> searching{0.};
    double                                time = 0.; ///< load factor
    std::vector<std::string>              messages;
    dealii::IndexSet                      multipliers;
    dealii::types::global_dof_index       total_multipliers  = 0;
    double                                max_youngs_modulus = 0.;
    /// Hard contact holds closed nodes at this gap, 1e-10 times the scene
    /// size, instead of exactly 0: a node that touches the master up to
    /// round-off (a body resting on a point) then counts as closed instead
    /// of leaving the body floating with a singular stiffness matrix.
    double clearance = 0.;
  };
} // namespace glide
