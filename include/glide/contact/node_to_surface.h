#pragma once

#include <glide/contact/formulation.h>

#include <cstdint>
#include <limits>
#include <vector>

namespace glide
{
  /**
   * Node to surface, finite sliding (R1-R5; doc/theory/node-to-surface.md):
   * the gap of each slave node to its closest point on an analytical rigid
   * master or on the (smoothed) surface of a deformable or meshed rigid
   * master, searched at every iterate.
   *
   * History (commit_step()): the node's position and projection at the end
   * of the last converged step, for the slip. Holds (faceted masters, f =
   * 0): between two attempts at a step the driver may hold nodes on one
   * facet; their gap is then measured to that facet's plane until the step
   * ends (doc/theory/nonlinear-solution.md).
   */
  template <int dim>
  class NodeToSurfaceFinite : public Formulation<dim>
  {
  public:
    using Formulation<dim>::Formulation;
    using typename Formulation<dim>::Linearization;

    std::string
    name() const override
    {
      return "node to surface, finite sliding";
    }

    void
    setup(const std::vector<SlaveNode<dim>> &nodes) override;

    Constraint<dim>
    evaluate(const unsigned int i, const VectorType &U) const override;

    void
    linearize(const unsigned int     i,
              const Constraint<dim> &s,
              const VectorType      &U,
              Linearization         &l) const override;

    void
    couplings(const unsigned int                            i,
              const VectorType                             &U,
              std::vector<dealii::types::global_dof_index> &dofs) override;

    bool
    outside_pattern(const unsigned int     i,
                    const Constraint<dim> &s) const override;

    int
    holdable_piece(const Constraint<dim> &s) const override;

    void
    hold(const unsigned int i, const int piece, const int partner) override;

    void
    release_holds() override;

    bool
    slides() const override
    {
      return this->surface != nullptr;
    }

    unsigned int
    n_held() const override;
    int
    touched_facet(const unsigned int i, const Constraint<dim> &s) const override
    {
      (void)i;
      return this->surface && s.found() && s.projection.found ?
               static_cast<int>(
                 this->surface->get_pieces()[s.projection.piece].facet) :
               -1;
    }

    std::vector<typename Formulation<dim>::HeldGap>
    held_gaps(const std::vector<Constraint<dim>> &s) const override;

    void
    commit_step(const VectorType                   &U,
                const std::vector<Constraint<dim>> &s,
                const std::vector<bool>            &closed,
                const double                        t_old,
                const double                        t_new) override;

    void
    read_dofs(
      std::vector<dealii::types::global_dof_index> &dofs) const override;

  protected:
    void
    renumber_pieces(const std::vector<std::uint64_t> &old_keys) override;

  private:
    /// The master's material point at projection @p p (empty if not
    /// found), with the DoF values of @p U (empty: zero).
    MaterialPoint<dim>
    material_point(const typename MasterSurface<dim>::Projection &p,
                   const VectorType                              &U) const;

    /// Distance of constraint @p s from the end of its piece along the
    /// piece's tangent plane (0 inside the piece).
    static double
    past_end(const Constraint<dim> &s);

    /// Per node: master nodes coupled in the sparsity pattern (sorted).
    std::vector<std::vector<unsigned int>> coupled;
    /// Per node: position at the end of the last converged step, and
    /// (deformable and meshed rigid masters) the master's material point
    /// under it then (empty: none).
    std::vector<dealii::Point<dim>> previous_position;
    std::vector<MaterialPoint<dim>> previous_point;
    /// Deformable faceted masters: per node, the piece it is held on (-1:
    /// none), set by hold() between two attempts at a step. At a faceted
    /// corner the force direction jumps between the facets' normals, and
    /// Newton can alternate between them forever (f = 0 only: a smoothed
    /// master has no corners). One-facet holds end with the step (vertex
    /// holds closed at their vertex go on, `carried`). Carrying those
    /// still within 2 % of a facet of their piece into the next step was
    /// tried: the faceted ironing die's press took 10 instead of 39
    /// cut-backs, but the full ironing run then stopped at load factor
    /// 0.785 (it finishes without). Holding on without such a band let the
    /// held nodes accumulate: the 2D Hertz peak pressure with f = 0 went
    /// from 2 % to 12 % too high, and the ironing die's nodes ended up 1.7
    /// past their facets.
    std::vector<int> held_piece;
    /// Per node: the piece it alternated with, where it is held at the
    /// vertex the two share (MasterSurface::project_at_vertex()); -1: on
    /// held_piece alone.
    std::vector<int> held_partner;
    /// Per node: held at a vertex and closed there at the end of the last
    /// converged step, so that the hold goes on (release_holds()).
    std::vector<bool> carried;
    /// The projection of node @p i at @p x: free, or as it is held.
    typename MasterSurface<dim>::Projection
    held_projection(const unsigned int i, const dealii::Point<dim> &x) const;
    /// Deformable masters: per node, the last projection with the slave
    /// position, master version() and held piece it was computed for (the
    /// residual and the Jacobian of one iterate share it; a cache of a pure
    /// function, not state).
    struct CachedProjection
    {
      typename MasterSurface<dim>::Projection projection;
      dealii::Point<dim>                      x;
      std::uint64_t version = std::numeric_limits<std::uint64_t>::max();
      int           held    = -1;
      int           partner = -1;
    };
    mutable std::vector<CachedProjection> cached;
  };
} // namespace glide
