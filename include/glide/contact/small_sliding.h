#pragma once

#include <glide/contact/master_surface.h>

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/numerics/rtree.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace glide
{
  /**
   * Local tangent directions at a contact point with normal @p n (R13.1),
   * by a fixed convention: in 2D t1 = e_z x n (the master's direction of
   * increasing parameter); in 3D t1 is the global x axis projected onto the
   * tangent plane (the z axis if x is within 0.1 degrees of n), t2 = n x
   * t1. Finite sliding evaluates them at the current normal; small sliding
   * evaluates them once at the anchor and then turns them with the master
   * facet.
   */
  template <int dim>
  std::array<dealii::Tensor<1, dim>, dim - 1>
  contact_tangents(const dealii::Tensor<1, dim> &n);

  /**
   * Surface-to-surface contact direction (R9.2, R9.3): from the anchor
   * @p anchor to the averaging region's centre @p centre, oriented against
   * the slave normal @p slave_normal (along -slave_normal where the two
   * points are closer than @p tolerance), with the components normal to
   * the symmetry planes marked in @p symmetric removed; unit length.
   */
  template <int dim>
  dealii::Tensor<1, dim>
  contact_direction(const dealii::Point<dim>     &centre,
                    const dealii::Point<dim>     &anchor,
                    const dealii::Tensor<1, dim> &slave_normal,
                    const std::array<bool, dim>  &symmetric,
                    const double                  tolerance)
  {
    dealii::Tensor<1, dim> n = centre - anchor;
    if (n.norm() <= tolerance)
      n = -slave_normal;
    if (n * slave_normal > 0.)
      n = -n;
    for (unsigned int c = 0; c < dim; ++c)
      if (symmetric[c])
        n[c] = 0.;
    return n / n.norm();
  }

  /**
   * Small-sliding node-to-surface contact against the master surface of a
   * deformable (or meshed rigid) body (issue 4; R6-R8, R10-R12; equations
   * in doc/theory/small-sliding.md).
   *
   * Nodal normals of the master are the normalized mean of the normals of
   * the master facets at each node, in the initial configuration (R7.1);
   * at perimeter nodes with XSYMM/YSYMM/ZSYMM (or on the axis of an
   * axisymmetric scene) the component normal to the symmetry plane is
   * removed (R8.2); user normals replace both (R8.1). On a facet the
   * smooth normal field N(xi) interpolates the nodal normals with the
   * facet's shape functions (R7.2). The anchor X0 of a slave node is the
   * facet point whose N(X0) passes through the node, found once before the
   * first step (R7.3); the tangent plane through X0 is normal to N0 =
   * N(X0).
   *
   * Finite rotations (small sliding, R6.1, R10.1): the anchor keeps its
   * parameters xi0 in its facet, x0 = sum_j N_j(xi0) x_j, and the plane
   * normal keeps its components in the facet's orthonormal frame at xi0
   * (e1 along the first tangent, e_n the facet normal), so it moves and
   * rotates with the facet. The gap is g = (x_s - x0) . n. The load goes
   * to the fixed node list of R11.1 (the anchor facet's nodes; at a master
   * node, that node and all nodes of the facets around it), shared by the
   * facet's shape functions at the parameters of the slave node's
   * projection onto the plane (its centre of action, R11.2), clamped to the
   * facet, so the list never grows (R11.3). The Jacobian is the exact
   * derivative of this residual (automatic differentiation).
   *
   * Infinitesimal sliding (geometrically linear scenes, R6.3): the plane
   * and the weights w0 are those of the initial configuration and never
   * change: g = (x_s - X0 - sum_j w0_j u_j) . N0, a linear constraint
   * whose force vector (N0 at the slave, -w0_j N0 at the master nodes) is
   * its gradient.
   */
  template <int dim>
  class SmallSliding
  {
  public:
    using Xi            = std::array<double, dim - 1>;
    using Linearization = typename MasterSurface<dim>::Linearization;

    struct Anchor
    {
      bool         found = false;
      unsigned int facet = 0;  ///< facet that holds X0
      Xi           xi    = {}; ///< parameters of X0 in it
      int          node  = -1; ///< master node where X0 is at a node
      /// Fixed master nodes of the constraint (sorted) and the facets whose
      /// shape functions share the load (the anchor facet first).
      std::vector<unsigned int> list;
      std::vector<unsigned int> facets;
      dealii::Point<dim>        X0;
      dealii::Tensor<1, dim>    N0;
      /// N0 and the initial local tangent directions (R13.1) in the anchor
      /// facet's orthonormal frame at xi (reference).
      std::array<double, dim>                      frame         = {};
      std::array<std::array<double, dim>, dim - 1> tangent_frame = {};
      /// Load-transfer weights over `list` in the initial configuration
      /// (used throughout in infinitesimal sliding).
      std::vector<double> weights;
      /// Distance along the plane from the anchor beyond which the slide is
      /// reported as not small (R12.2).
      double limit = 0.;
      /// Surface to surface (R9): the slave nodes of the averaging region
      /// (indices in the caller's slave node list, the constraint's own
      /// node first) and their constant participation factors; the master
      /// weights are those of the region's landing zone, fixed.
      bool                      sts = false;
      std::vector<unsigned int> region;
      std::vector<double>       participation;
    };

    /// Why a surface-to-surface constraint falls back to node to surface
    /// (R9.4; a node-based slave surface is the caller's case).
    enum class Fallback
    {
      none,
      missed,        ///< the projection along the slave normal misses
      same_direction ///< slave and master normals point the same way
    };

    /// @p user_normals: master node index -> prescribed normal (R8.1).
    SmallSliding(
      const MasterSurface<dim>                             &surface,
      const std::map<unsigned int, dealii::Tensor<1, dim>> &user_normals,
      const bool                                            infinitesimal,
      const bool                                            axisymmetric);

    /// Anchor of the slave node at reference position @p X (R7.3); not
    /// found if no N(x) of the master passes through it.
    Anchor
    anchor(const dealii::Point<dim> &X) const;

    /// Surface-to-surface anchor (R9.1-R9.3) of the averaging region with
    /// initial positions @p X (the constraint's own node first) and
    /// participation factors @p phi: each node projected along the slave
    /// normal @p slave_normal (outward, towards the master) lands on the
    /// master; the anchor is the participation-weighted centre of the
    /// landing points, the contact direction runs from it to the region's
    /// weighted centre (along -slave_normal where they coincide) and lies
    /// in the symmetry planes marked in @p symmetric. Not found, with
    /// @p reason, where a region node's projection misses the master or
    /// the master normal points the way of the slave normal.
    Anchor
    anchor_sts(const std::vector<dealii::Point<dim>> &X,
               const std::vector<double>             &phi,
               const dealii::Tensor<1, dim>          &slave_normal,
               const std::array<bool, dim>           &symmetric,
               Fallback                              &reason) const;

    /// Nodal normals of the master (R7.1, R8).
    const std::vector<dealii::Tensor<1, dim>> &
    nodal_normals() const
    {
      return normals;
    }

    /// Empty, or which user normal (R8.1) points into the master (the
    /// caller reports it as an input error, on every process).
    const std::string &
    inward_user_normal() const
    {
      return inward;
    }

    /// The smooth normal field N(xi) on facet @p facet (R7.2).
    dealii::Tensor<1, dim>
    normal_field(const unsigned int facet, const Xi &xi) const;

    /// Current anchor point, plane normal, local tangent directions and
    /// gap of a slave node at @p x (master at its current positions).
    struct Plane
    {
      dealii::Point<dim>                          point;
      dealii::Tensor<1, dim>                      normal;
      std::array<dealii::Tensor<1, dim>, dim - 1> tangents;
      double                                      gap = 0.;
      std::vector<double> weights; ///< load-transfer weights over the list
    };
    Plane
    plane(const Anchor &a, const dealii::Point<dim> &x) const;

    /// Surface to surface: the gap of the constraint's own slave node at
    /// @p x to the master point where it landed at set-up (a.facet, a.xi),
    /// at the current positions, along @p normal. The constraint's gap is
    /// the region's weighted mean, which on a convex master lies about
    /// h^2 / (3 R) above this one.
    double
    landing_gap(const Anchor                 &a,
                const dealii::Point<dim>     &x,
                const dealii::Tensor<1, dim> &normal) const;

    /// Current load-transfer weights over `a.list` for a slave node at @p x
    /// (R11.2).
    std::vector<double>
    weights(const Anchor &a, const dealii::Point<dim> &x) const;

    /// Gap and force vector with their derivatives (slave DoFs first, then
    /// the list's master nodes). @p slaves: DoFs and current position of
    /// the constraint's slave node, or (surface to surface) of every node
    /// of its averaging region in the order of `a.region`.
    using SlaveDofs = std::array<dealii::types::global_dof_index, dim>;
    void
    linearize(
      const Anchor                                                &a,
      const std::vector<std::pair<SlaveDofs, dealii::Point<dim>>> &slaves,
      Linearization                                               &l) const;

    bool
    is_infinitesimal() const
    {
      return infinitesimal;
    }

  private:
    /// Gap, plane normal, anchor point and weights over the list for the
    /// slave point @p xs with master node positions @p pos.
    template <typename T, typename Positions>
    void
    evaluate(const Anchor             &a,
             const std::array<T, dim> &xs,
             const Positions          &pos,
             const bool                fixed_plane,
             T                        &gap,
             std::array<T, dim>       &n,
             std::array<T, dim>       &x0,
             std::vector<T>           &w) const;

    /// plane() at the current positions, or at the initial ones if
    /// @p initial (then with the plane of small sliding).
    Plane
    evaluate_plane(const Anchor             &a,
                   const dealii::Point<dim> &x,
                   const bool                initial) const;

    /// Orthonormal frame of the anchor facet of @p a at its anchor
    /// parameters, at the current positions (initial positions if
    /// @p initial).
    std::array<dealii::Tensor<1, dim>, dim>
    anchor_frame(const Anchor &a, const bool initial) const;

    /// Call @p visit(facet) for the facets near @p X, then further away,
    /// until it returns true for one (after the current ring) or every
    /// facet has been visited once.
    template <typename Visit>
    void
    search(const dealii::Point<dim> &X, const Visit &visit) const;

    /// The point where the line X + t d meets the master (smallest |t|):
    /// facet, parameters and t; false if it misses.
    bool
    ray(const dealii::Point<dim>     &X,
        const dealii::Tensor<1, dim> &d,
        unsigned int                 &facet,
        Xi                           &xi,
        double                       &t) const;

    /// Frame, tangent frame and slide limit of @p a from its facet, its
    /// parameters and N0 (initial configuration).
    void
    set_frame(Anchor &a) const;

    /// Point and tangents of facet @p facet at @p xi for node positions
    /// @p pos.
    template <typename T, typename Positions>
    void
    facet_point(const unsigned int                       facet,
                const Xi                                &xi,
                const Positions                         &pos,
                std::array<T, dim>                      &x,
                std::array<std::array<T, dim>, dim - 1> &A) const;

    /// Newton for the anchor on facet @p facet; false if none there.
    bool
    anchor_on(const unsigned int        facet,
              const dealii::Point<dim> &X,
              Xi                       &xi,
              double                   &distance) const;

    const MasterSurface<dim>              &surface;
    const bool                             infinitesimal;
    std::vector<dealii::Tensor<1, dim>>    normals;
    std::string                            inward; ///< inward_user_normal()
    std::vector<std::vector<unsigned int>> node_facets;
    using Leaf = std::pair<dealii::BoundingBox<dim>, unsigned int>;
    dealii::RTree<Leaf> tree; ///< facets, initial configuration
  };
} // namespace glide
