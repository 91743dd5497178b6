#pragma once

#include <glide/contact/master_surface.h>
#include <glide/contact/rigid_master.h>
#include <glide/mechanics/elasticity.h>
#include <glide/scene/scene.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace glide
{
  /// A slave node of a contact pair (locally owned), with what every
  /// formulation and enforcement needs to know of it.
  template <int dim>
  struct SlaveNode
  {
    dealii::Point<dim>                               X;
    std::array<dealii::types::global_dof_index, dim> dofs;
    double area = 0.; ///< tributary area int N_a dA
    /// int |N_a| dA: positive where the tributary area vanishes, the corner
    /// node on the axis of a quadratic axisymmetric facet (int N r dr = 0)
    double measure = 0.;
    /// Whether the node has no tributary area of its own: int N_a dA at
    /// most a tenth of int |N_a| dA. Only the corner node on the axis of a
    /// quadratic axisymmetric facet (0 on a straight facet, a few 1e-3 of
    /// it on a curved one); any other node has at least 0.44 of it (a
    /// corner of a quadratic 3D face; 2/3 in 2D, 1 for degree 1).
    bool
    without_area() const
    {
      return !(area > 0.1 * measure);
    }
    double size = 0.; ///< mean size of the adjacent slave facets
    /// First multiplier of the node's block (hard enforcement: the normal
    /// force; friction will add dim - 1 tangential ones).
    dealii::types::global_dof_index multiplier =
      dealii::numbers::invalid_dof_index;
    double c = 0.; ///< NCP constant E_pair A / h
    double k = 0.; ///< penalty stiffness * area
    /// Surface slaves: area-weighted outward normal, and int N_a N_b dA
    /// with the neighbours b on the slave surface (keyed by x DoF).
    dealii::Tensor<1, dim>                            normal;
    std::map<dealii::types::global_dof_index, double> mass;
    /// Hanging nodes of the slave surface (keyed by x DoF) whose area went
    /// to this node, with their constraint weights
    /// (Contact::condense_hanging_nodes): mortar adds their weighted
    /// terms to this node's.
    std::vector<std::pair<dealii::types::global_dof_index, double>> hanging;
  };

  /// A point of the master's material as a linear combination of DoF
  /// values, recorded at the end of a step (the slip, R12: the slave node's
  /// motion relative to the material that was under it). Its motion since
  /// is, per component, sum weight * (U[dof] - value). Read through DoFs,
  /// not through the facets a process holds, so that under MPI it moves
  /// with the master also after the slave slid out of their reach.
  template <int dim>
  struct MaterialPoint
  {
    struct Term
    {
      dealii::types::global_dof_index dof;
      double                          weight;
      double                          value; ///< U[dof] when recorded
    };
    std::array<std::vector<Term>, dim> terms;

    bool
    empty() const
    {
      return terms[0].empty();
    }
    void
    clear()
    {
      for (auto &t : terms)
        t.clear();
    }
    /// Adds weight * (the DoF's value) to component @p d.
    void
    add(const unsigned int                    d,
        const dealii::types::global_dof_index dof,
        const double                          weight,
        const VectorType                     &U)
    {
      terms[d].push_back({dof, weight, U.size() > 0 ? U[dof] : 0.});
    }
    /// The motion since it was recorded, at @p U.
    dealii::Tensor<1, dim>
    motion(const VectorType &U) const
    {
      dealii::Tensor<1, dim> m;
      for (unsigned int d = 0; d < dim; ++d)
        for (const auto &t : terms[d])
          m[d] += t.weight * (U[t.dof] - t.value);
      return m;
    }
    void
    dofs(std::vector<dealii::types::global_dof_index> &out) const
    {
      for (const auto &component : terms)
        for (const auto &t : component)
          out.push_back(t.dof);
    }
  };

  /// Why a constraint exists or not at an iterate (house style: an explicit
  /// outcome that callers handle and the statistics count, R16.3).
  enum class Outcome
  {
    found,      ///< the slave point has a gap to the master
    beyond_end, ///< projects beyond the end of the master: open
    failed,     ///< the closest-point iteration did not converge: open
    unanchored, ///< small sliding without an anchor (R7.4): never closes
    /// a boundary condition prescribes the motion along the constraint's
    /// force direction (Contact::mark_prescribed()): never closes
    prescribed
  };

  /// The geometry of one constraint at an iterate: what a formulation
  /// computes from U and its committed history alone.
  template <int dim>
  struct Constraint
  {
    Outcome                outcome = Outcome::found;
    dealii::Point<dim>     x; ///< current slave node position
    double                 gap = 0.;
    dealii::Tensor<1, dim> normal;
    /// The constraint's slave point: the node, or (surface to surface) the
    /// weighted centre of its averaging region.
    dealii::Point<dim> point;
    dealii::Point<dim> anchor; ///< small sliding: current anchor point
    /// Local tangent directions (R13.1).
    std::array<dealii::Tensor<1, dim>, dim - 1> tangents;
    /// Mortar: the share of the node's weight (int N dA over its slave
    /// facets) that the master covers; below 1 where the master ends
    /// inside the node's facets. 1 for the other formulations.
    double coverage = 1.;
    /// Finite sliding: the projection (rigid analytical or deformable).
    typename RigidMaster<dim>::Projection   rigid;
    typename MasterSurface<dim>::Projection projection;

    bool
    found() const
    {
      return outcome == Outcome::found;
    }
  };

  /// What a formulation of one contact pair gets from the contact part.
  template <int dim>
  struct PairContext
  {
    const Scene                 &scene;
    const Elasticity<dim>       &elasticity;
    MPI_Comm                     comm;
    const ContactPairParameters &parameters;
    std::string                  path; ///< "Contact pair <name>"
    /// Log a list of nodes (gathered over all processes) as
    /// before + count + after + ": " + list; nothing if the list is empty.
    std::function<void(const std::vector<std::string> &,
                       const std::string &,
                       const std::string &)>
      report;
    /// Log one message (first process only).
    std::function<void(const std::string &)> note;
  };

  /**
   * One contact formulation of one pair (DESIGN.md, "The contact part,
   * second generation"): it turns the current iterate into constraints,
   * one per slave node: the gap, its derivative and where the force goes
   * (evaluate(), linearize()). It reads only U, the load factor, the holds
   * of the current attempt and the history stored by commit_step(), so
   * that the residual is a function of the iterate (R16.1). The
   * enforcement (hard, penalty) is not its business.
   *
   * Formulations are chosen by name (make_formulation()): "node to
   * surface, finite sliding" (NodeToSurfaceFinite), "node to surface,
   * small sliding" and "surface to surface, small sliding"
   * (SmallSlidingFormulation).
   */
  template <int dim>
  class Formulation
  {
  public:
    using Linearization = typename MasterSurface<dim>::Linearization;

    Formulation(const PairContext<dim>             &context,
                std::unique_ptr<RigidMaster<dim>>   master,
                std::unique_ptr<MasterSurface<dim>> surface);

    virtual ~Formulation() = default;

    /// The name of the formulation as the scene writes it, e.g. "node to
    /// surface, finite sliding".
    virtual std::string
    name() const = 0;

    /// Set up the formulation's data for the slave nodes @p nodes (kept by
    /// reference: the vector must outlive the formulation and not change).
    virtual void
    setup(const std::vector<SlaveNode<dim>> &nodes);

    /// Move rigid masters to load factor @p t.
    void
    set_time(const double t);

    /// Move a deformable master to iterate @p U.
    virtual void
    move(const VectorType &U) const;

    /// The constraint of slave node @p i at iterate @p U (move() must have
    /// been called with U).
    virtual Constraint<dim>
    evaluate(const unsigned int i, const VectorType &U) const = 0;

    /// Gap, force direction and their derivatives of constraint @p s of
    /// node @p i at iterate @p U (s.found() only).
    virtual void
    linearize(const unsigned int     i,
              const Constraint<dim> &s,
              const VectorType      &U,
              Linearization         &l) const = 0;

    /// The DoFs the constraint of node @p i couples with (besides the
    /// node's own and its multipliers), for the sparsity pattern; @p U is
    /// the iterate the pattern is built at (empty before the first solve).
    virtual void
    couplings(const unsigned int                            i,
              const VectorType                             &U,
              std::vector<dealii::types::global_dof_index> &dofs);

    /// The displacement DoFs the formulation reads from an iterate besides
    /// the DoFs and multipliers of this process's slave nodes (those of
    /// the master surface's nodes): under MPI they are imported as ghosts.
    virtual void
    read_dofs(std::vector<dealii::types::global_dof_index> &dofs) const;

    /// True if constraint @p s of node @p i reaches DoFs outside those of
    /// the last couplings().
    virtual bool
    outside_pattern(const unsigned int i, const Constraint<dim> &s) const;

    /// The master piece of constraint @p s that the driver may hold the
    /// node on (faceted deformable masters), by its key
    /// (MasterSurface::piece_key(), which a new gather does not change);
    /// -1: none.
    virtual int
    holdable_piece(const Constraint<dim> &s) const;

    /// Hold node @p i on the piece with key @p piece for the rest of the
    /// step, or, where the formulation can, at the vertex that piece shares
    /// with the piece with key @p partner (-1: none), which it alternated
    /// with.
    virtual void
    hold(const unsigned int i, const int piece, const int partner);

    /// Under MPI: whether the master facets a slave node reaches change as
    /// it slides (finite sliding), so that Contact gathers them again as
    /// the nodes go (R15.2). Small sliding reaches its anchors' facets
    /// only, gathered once.
    virtual bool
    slides() const
    {
      return false;
    }

    /// Collective: gather the master facets within @p regions again
    /// (MasterSurface::gather_near(); @p U with the DoFs of read_dofs()),
    /// and carry whatever refers to the old pieces over to the new ones.
    void
    regather(const VectorType                            &U,
             const std::vector<dealii::BoundingBox<dim>> &regions);

    /// End all holds.
    virtual void
    release_holds();

    /// Number of held nodes.
    virtual unsigned int
    n_held() const;

    /// A held node's gap error: the difference between its gap
    /// (constraint, measured to the plane of the facet it is held on) and
    /// its gap to the master (the free projection's; the facet's length
    /// where that finds none), and the facet's length.
    struct HeldGap
    {
      unsigned int node;
      double       error;
      double       facet_length;
    };
    /// The gap errors of the held nodes at constraints @p s (none without
    /// holds).
    virtual std::vector<HeldGap>
    held_gaps(const std::vector<Constraint<dim>> &s) const;

    /// Constraints that fell back to a simpler formulation (R9.4).
    virtual unsigned int
    n_fallbacks() const;

    /// The gap of slave node @p i itself at the state of its constraint
    /// @p s: for an averaged constraint (surface to surface) its distance
    /// to where it lands on the master, along the constraint's normal;
    /// otherwise the constraint's gap.
    virtual double
    own_gap(const unsigned int i, const Constraint<dim> &s) const
    {
      (void)i;
      return s.gap;
    }

    /// The facet of master_surface() whose nodes take the force of
    /// constraint @p s of node @p i (node to surface: the projection's;
    /// small sliding: the anchor's), -1 where there is none.
    virtual int
    touched_facet(const unsigned int i, const Constraint<dim> &s) const
    {
      (void)i;
      (void)s;
      return -1;
    }

    /// True if the force of constraint @p i acts on slave node i alone,
    /// with the master nodes (node to surface, mortar's dual basis): then
    /// the multipliers can be eliminated (MultiplierCondensation).
    virtual bool
    force_on_own_node() const
    {
      return true;
    }

    /// Add the normal force @p lambda of constraint @p i to the nodal
    /// forces @p nodal of this process's slave nodes (surface to surface:
    /// shared over its region). Under MPI the shares of slave nodes of
    /// other processes go to @p elsewhere, keyed by the node's x DoF.
    virtual void
    distribute(const unsigned int   i,
               const double         lambda,
               std::vector<double> &nodal,
               std::vector<std::pair<dealii::types::global_dof_index, double>>
                 &elsewhere) const;

    /// After a converged step from load factor @p t_old to @p t_new, with
    /// the constraints @p s and the closed flags @p closed at the converged
    /// iterate: accumulate slip (R12) and store the history the next step
    /// starts from (positions, projections, offsets).
    virtual void
    commit_step(const VectorType                   &U,
                const std::vector<Constraint<dim>> &s,
                const std::vector<bool>            &closed,
                const double                        t_old,
                const double                        t_new) = 0;

    /// Accumulated slip CSLIP and its components CSLIP1 (, CSLIP2).
    const std::vector<double> &
    slip() const
    {
      return slip_length;
    }
    const std::vector<std::array<double, 2>> &
    slip_components() const
    {
      return slip_parts;
    }

    /// Wall time spent in searches (R-tree set-up and projections), in
    /// seconds.
    double
    search_time() const
    {
      return searching.count();
    }

    /// The analytical rigid master, if any.
    const RigidMaster<dim> *
    rigid_master() const
    {
      return master.get();
    }

    /// The master surface of a deformable (or meshed rigid) body, if any.
    const MasterSurface<dim> *
    master_surface() const
    {
      return surface.get();
    }

  protected:
    /// After regather(): refer to the new pieces; @p old_keys gives the
    /// key of each old piece (MasterSurface::piece_key()).
    virtual void
    renumber_pieces(const std::vector<std::uint64_t> &old_keys)
    {
      (void)old_keys;
    }

    /// Add the tangential part of the relative motion @p relative of node
    /// @p i to its slip, with components along the tangents of @p normal.
    void
    accumulate_slip(const unsigned int            i,
                    const dealii::Tensor<1, dim> &normal,
                    const dealii::Tensor<1, dim> &relative);

    /// The current position of node @p i.
    dealii::Point<dim>
    position(const unsigned int i, const VectorType &U) const;

    /// Log the slave nodes whose constraint in @p s failed (R16.3), by
    /// their reference positions, as "@p what did not converge for N slave
    /// node(s) ...".
    void
    report_failed(const std::vector<Constraint<dim>> &s,
                  const std::string                  &what) const;

    PairContext<dim>                      context;
    std::unique_ptr<RigidMaster<dim>>     master;
    std::unique_ptr<MasterSurface<dim>>   surface;
    const std::vector<SlaveNode<dim>>    *nodes = nullptr;
    double                                time  = 0.;
    std::vector<double>                   slip_length;
    std::vector<std::array<double, 2>>    slip_parts;
    mutable std::chrono::duration<double> searching{0.};
  };

  /// The formulation that the pair's parameters name ('Formulation' and
  /// 'Sliding'), with its master.
  template <int dim>
  std::unique_ptr<Formulation<dim>>
  make_formulation(const PairContext<dim>             &context,
                   std::unique_ptr<RigidMaster<dim>>   master,
                   std::unique_ptr<MasterSurface<dim>> surface);
} // namespace glide
