#pragma once

#include <glide/contact/formulation.h>
#include <glide/contact/small_sliding.h>

#include <vector>

namespace glide
{
  /**
   * Small sliding (R6-R12; doc/theory/small-sliding.md): each constraint
   * measures its gap to a tangent plane through an anchor found once before
   * the first step; the plane turns with the master and the load goes to a
   * fixed list of master nodes. Node to surface: one constraint per slave
   * node. Surface to surface (R9): the constraint's slave point is the
   * participation-weighted centre of the node's averaging region on the
   * slave surface, falling back to node to surface per constraint where
   * that fails (R9.4, counted).
   *
   * History (commit_step()): the tangential offset of each slave point from
   * its anchor at the end of the last converged step, for the slip, and
   * which nodes were warned about sliding too far (R12.2).
   */
  template <int dim>
  class SmallSlidingFormulation : public Formulation<dim>
  {
  public:
    using typename Formulation<dim>::Linearization;

    /// @p surface_to_surface: averaging regions (R9) instead of nodes.
    SmallSlidingFormulation(const PairContext<dim>             &context,
                            std::unique_ptr<RigidMaster<dim>>   master,
                            std::unique_ptr<MasterSurface<dim>> surface,
                            const bool surface_to_surface);

    std::string
    name() const override
    {
      return surface_to_surface ? "surface to surface, small sliding" :
                                  "node to surface, small sliding";
    }

    void
    setup(const std::vector<SlaveNode<dim>> &nodes) override;

    void
    move(const VectorType &U) const override;

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

    unsigned int
    n_fallbacks() const override;
    double
    own_gap(const unsigned int i, const Constraint<dim> &s) const override;
    int
    touched_facet(const unsigned int i, const Constraint<dim> &s) const override
    {
      return s.found() && anchors[i].found ?
               static_cast<int>(anchors[i].facet) :
               -1;
    }

    /// Surface to surface spreads the force of a constraint over the
    /// nodes of its averaging region.
    bool
    force_on_own_node() const override
    {
      return !surface_to_surface;
    }

    void
    distribute(const unsigned int   i,
               const double         lambda,
               std::vector<double> &nodal,
               std::vector<std::pair<dealii::types::global_dof_index, double>>
                 &elsewhere) const override;

    /// Also the DoFs of the slave nodes of other processes in this
    /// process's averaging regions.
    void
    read_dofs(
      std::vector<dealii::types::global_dof_index> &dofs) const override;

    void
    commit_step(const VectorType                   &U,
                const std::vector<Constraint<dim>> &s,
                const std::vector<bool>            &closed,
                const double                        t_old,
                const double                        t_new) override;

    /// The anchors of the locally owned slave nodes (for tests).
    const std::vector<typename SmallSliding<dim>::Anchor> &
    get_anchors() const
    {
      return anchors;
    }

  private:
    /// R12.2's limit of the slide from the anchor on an analytical rigid
    /// master, for a slave node of facet size @p size: that size, less
    /// where a circle, cylinder or sphere turns by 10 degrees (infinite
    /// for a plane).
    double
    sliding_limit(const double size) const;

    /// Small-sliding anchor on an analytical rigid master: the closest
    /// point of @p X and the master normal there (initial position);
    /// @p size is the node's facet size (sliding_limit()).
    typename SmallSliding<dim>::Anchor
    rigid_anchor(const dealii::Point<dim> &X, const double size) const;

    /// Surface-to-surface anchor on an analytical rigid master (R9.2 with
    /// the closest points as the landing points).
    typename SmallSliding<dim>::Anchor
    rigid_anchor_sts(const std::vector<dealii::Point<dim>> &X,
                     const std::vector<double>             &phi,
                     const dealii::Tensor<1, dim>          &slave_normal,
                     const std::array<bool, dim>           &symmetric,
                     typename SmallSliding<dim>::Fallback  &reason,
                     const double                           size) const;

    /// Surface-to-surface anchors (R9), with the fall-back to node to
    /// surface counted in the log (R9.4).
    void
    setup_surface_to_surface();

    /// Surface to surface under MPI: a slave node of another process in
    /// an averaging region (region index nodes.size() + k is
    /// neighbours[k]).
    struct Neighbour
    {
      dealii::Point<dim>                               X;
      std::array<dealii::types::global_dof_index, dim> dofs;
    };

    /// Reference position and DoFs of region node @p k.
    const dealii::Point<dim> &
    region_X(const unsigned int k) const;
    const std::array<dealii::types::global_dof_index, dim> &
    region_dofs(const unsigned int k) const;
    /// Current position of region node @p k.
    dealii::Point<dim>
    region_position(const unsigned int k, const VectorType &U) const;

    const bool             surface_to_surface;
    std::vector<Neighbour> neighbours;
    /// The anchors and tangent planes, per node (for analytical rigid
    /// masters only X0 and N0 are used).
    std::unique_ptr<SmallSliding<dim>>              planes;
    std::vector<typename SmallSliding<dim>::Anchor> anchors;
    /// Tangential coordinates of the slave point relative to its anchor at
    /// the end of the last converged step (along the plane's tangents).
    std::vector<std::array<double, 2>> previous_offset;
    std::vector<bool>                  warned;
  };
} // namespace glide
