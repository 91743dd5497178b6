#pragma once

#include <glide/mechanics/elasticity.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/rtree.h>

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace glide
{
  /// The nodes of face @p f of @p cell: per node (keyed by its base index
  /// in the vector-valued element), the cell-local DoF index of each
  /// displacement component.
  template <int dim>
  std::map<unsigned int, std::array<unsigned int, dim>>
  face_node_indices(
    const dealii::FiniteElement<dim>                             &fe,
    const typename dealii::DoFHandler<dim>::active_cell_iterator &cell,
    const unsigned int                                            f);

  /// Boxes that cover @p points grown by @p reach in every direction: one
  /// per occupied cell of a grid of 16 cells along the longest side of the
  /// points' box (cells at least 2 @p reach wide), the box of the points in
  /// it, so that the points of one process that lie far apart (a partition
  /// that wraps around a surface) do not ask for everything between them.
  /// Empty if there are no points.
  template <int dim>
  std::vector<dealii::BoundingBox<dim>>
  covering_boxes(const std::vector<dealii::Point<dim>> &points,
                 const double                           reach);

  /**
   * The master surface of a contact pair on a deformable body (issue 3,
   * R1-R3): its facets, extracted from the boundary faces of degree 1 or 2
   * with outward orientation, the smoothing of R1, the search (deal.II's
   * R-tree over the pieces' bounding boxes) and the projection of a slave
   * point, and the linearization of gap and contact force with respect to
   * the slave and master displacements.
   *
   * The surface is a list of *pieces*, each a parametric patch
   *   x(xi) = sum_j w_j(xi) v_j,
   * with v_j a master node position or, at a symmetry plane, its mirror
   * image. In 2D (plane strain, axisymmetric) the pieces are the facets
   * shortened by f on each smoothed side and, between them, the transition
   * curves of R1.1: a cubic Hermite curve from x1(1 - f) to x2(f) with end
   * tangents 2 f x1'(1 - f) and 2 f x2'(f), which is tangent to both facets
   * and is exactly the parabola with control points x1(1-f), node, x2(f)
   * when the facets are straight. Transitions sit at the facets' end nodes,
   * never at mid-side nodes. A node between collinear linear facets gets
   * one too, but its control points are collinear, so the surface there is
   * exactly the facets (R1.2), and it stays smooth when the deforming
   * master develops a kink at that node. Between quadratic facets whose
   * reference tangents do not kink, the transition spans only
   * quadratic_fraction of each facet (build_pieces_2d() says why); a chain end
   * on a symmetry plane (XSYMM/YSYMM, or the axis of an axisymmetric scene) is
   * smoothed against the mirror image of its end facet (R2.1, R2.2). Smoothing
   * never crosses the end of the master surface (R3.1); there the end facet is
   * extended by 5 % of its parameter range, and a slave point beyond that is
   * not in contact.
   *
   * In 3D the pieces are the facets themselves; only the normal is
   * smoothed (R1.4): inside the lines at distance f from the edges (in the
   * facet's parameters) it is the facet's own normal, and towards the edges
   * and corners it blends, with the C1 step 3s^2 - 2s^3, into the edge
   * normal (mean of the two facets' normals at the edge midpoint) and the
   * corner normal (mean of the normals of all facets at the node). On a
   * symmetry plane (XSYMM/YSYMM/ZSYMM at the nodes) edge and corner normals
   * are projected into the plane, as the mirrored surface would give.
   *
   * Projection: the point x(xi) whose normal n(xi) passes through the
   * slave point, (r - (r.n) n).a_alpha = 0 with r = x_s - x(xi) and a_alpha
   * the tangents; Newton on xi per candidate piece, clamped to the piece.
   * The gap is g = r.n. Where no piece contains the projection but the
   * closest point is on an edge or node between pieces (a faceted corner,
   * f = 0), the pieces meeting there compete with their extended gaps
   * g = r.n (n: the piece's own normal at that point) and the largest |g|
   * wins: outside a convex corner a point is outside if it is outside any
   * facet's plane, inside a concave one it is inside if inside any. The
   * force direction stays a facet normal (n = r/|r| would turn as 1/|r|
   * next to the corner). Linearization: automatic differentiation (Sacado) of g
   * and of the force vector G (slave: n; master node j: -w_j n) through two
   * chord steps of the projection, which gives the exact first derivatives,
   * including the variation of projection point and normal (R5.1).
   */
  template <int dim>
  class MasterSurface
  {
  public:
    using Xi = std::array<double, dim - 1>;

    struct Node
    {
      dealii::Point<dim>                               X;
      std::array<dealii::types::global_dof_index, dim> dofs;
    };
    struct Facet
    {
      /// Nodes in lexicographic order of the facet's parameters; with
      /// outward normal a_1 x a_2 (3D) or (a_y, -a_x) (2D).
      std::vector<unsigned int> nodes;
      /// Neighbour facet across each side (2D: at xi = 0, xi = 1; 3D: the
      /// edges xi = 0, xi = 1, eta = 0, eta = 1), -1 at the surface boundary.
      std::array<int, 2 * (dim - 1)> neighbours;
      /// Its number in the whole surface: its place in the order of the
      /// facets' centres (sort_canonically()), whatever the partition, the
      /// order of the bodies and the mesh's numbering, and whichever facets
      /// a process holds. Ties between equally close
      /// pieces go to the lowest number, so they are decided alike on one
      /// process and on several.
      std::uint64_t key = 0;
    };
    /// What orders the facets (sort_canonically()): its centre in the
    /// reference configuration, then its cell (CellId::to_binary()) and
    /// face number.
    struct FacetId
    {
      std::array<double, dim>     centre{};
      std::array<unsigned int, 5> cell{};
      bool
      operator<(const FacetId &other) const
      {
        return std::tie(centre, cell) < std::tie(other.centre, other.cell);
      }
    };
    enum class PieceKind
    {
      lagrange, ///< a facet, or its part between xi_begin and xi_end (2D)
      hermite   ///< a transition curve (2D)
    };
    struct Piece
    {
      PieceKind    kind  = PieceKind::lagrange;
      unsigned int facet = 0;
      double       begin = 0.; ///< 2D lagrange: facet parameter range
      double       end   = 1.;
      Xi           lower = {}; ///< parameter range of the projection
      Xi           upper = {};
      /// Virtual nodes: (node, mirrored); hermite: coefficients of the four
      /// Hermite basis functions h00, h10, h01, h11.
      std::vector<std::pair<unsigned int, bool>> vnodes;
      std::vector<std::array<double, 4>>         coefficients;
      int          mirror_node = -1; ///< node on the symmetry plane
      unsigned int mirror_axis = 0;
      /// Which piece of its facet (piece_key()): 0 the facet, 1 the mirror
      /// transition at its start, 2 the transition to the next facet, 3 the
      /// mirror transition at its end.
      unsigned int role = 0;
    };
    struct Projection
    {
      /// The outcome (house style 16): found and inside a piece (vertex
      /// false), found and clamped at an edge or node (vertex true), or not
      /// found: beyond the end of the master (failed false), or because
      /// the closest-point iteration did not converge on a candidate piece
      /// (failed true). Contact counts each per step (R16.3).
      bool found  = false;
      bool failed = false;
      /// Found, but the closest-point iteration did not converge on
      /// another candidate piece near the point, which may hold a closer
      /// point than the one found (R16.3: counted and named like failed
      /// projections, `contact_<pair>_projection_incomplete`).
      bool         incomplete = false;
      bool         vertex     = false; ///< closest point on an edge/node
      unsigned int piece      = 0;
      Xi           xi         = {};
      std::array<bool, dim - 1> clamped = {};
      double                    gap     = 0.;
      dealii::Tensor<1, dim>    normal;
      dealii::Point<dim>        point;
      /// Held at the vertex that piece shares with piece `partner` (2D,
      /// faceted facets; project_at_vertex()); -1: not.
      int partner = -1;
    };
    /// Gap and contact force direction with their derivatives with respect
    /// to `dofs` (slave node first, then the master nodes).
    struct Linearization
    {
      std::vector<dealii::types::global_dof_index> dofs;
      double                                       gap = 0.;
      dealii::Tensor<1, dim>                       normal;
      dealii::Vector<double>                       dgap;
      dealii::Vector<double>                       force;
      dealii::FullMatrix<double>                   dforce;
      /// false: a residual only needs gap and force; a formulation may
      /// then leave dgap and dforce zero (sized as force) and save the
      /// cost of the derivatives (mortar: automatic differentiation).
      bool derivatives = true;
      /// Where dgap jumps (a faceted master, f = 0: the facet normal jumps
      /// at a vertex), a direction for the Jacobian stabilization of open
      /// nodes that is continuous along the surface: the slave node gets
      /// nu, master node j gets -w_j nu, with nu the interpolated averaged
      /// nodal normal. Empty where dgap itself serves.
      dealii::Vector<double> spring;
    };

    /// The master surface made of the boundary faces with ids @p ids.
    /// @p path names the contact pair in error messages.
    /// Under MPI every process holds the whole surface, unless
    /// @p distributed: then it keeps its own cells' facets aside and holds
    /// none until gather_near() brings those within reach of its slave
    /// nodes (R15.2).
    MasterSurface(const Elasticity<dim>                      &elasticity,
                  const std::set<dealii::types::boundary_id> &ids,
                  const double                                fraction,
                  const std::string                          &path,
                  const bool distributed = false);

    /// Distributed surfaces (collective): hold the facets of every process
    /// whose current bounding box meets one of @p regions, the boxes this
    /// process needs (none if empty; covering_boxes()), in the order of
    /// their keys, with their smoothing rebuilt. @p U must hold the DoFs of
    /// own_dofs(). Positions are reset to the reference ones and version()
    /// changes: the caller moves the surface again, after importing the new
    /// nodes' DoFs.
    void
    gather_near(const VectorType                            &U,
                const std::vector<dealii::BoundingBox<dim>> &regions);

    /// DoFs of the nodes of this process's own facets (distributed
    /// surfaces; empty otherwise).
    const std::vector<dealii::types::global_dof_index> &
    own_dofs() const
    {
      return own_node_dofs;
    }
    /// The largest change of a displacement component of own_dofs() since
    /// the last gather_near(), at @p U.
    double
    own_motion(const VectorType &U) const;
    /// Number of facets of the whole surface (on every process).
    std::uint64_t
    n_facets_global() const
    {
      return total_facets;
    }
    /// A number for piece @p piece that does not depend on which facets a
    /// process holds (its facet's key and its role), and the piece with
    /// key @p key here (-1: not held).
    std::uint64_t
    piece_key(const unsigned int piece) const
    {
      return 4 * facets[pieces[piece].facet].key + pieces[piece].role;
    }
    int
    find_piece(const std::uint64_t key) const;

    /// Current positions x = X + u (U: displacement first), and, if
    /// @p search, the search tree of the pieces' bounding boxes (small
    /// sliding never searches, R6.2). Positions that did not change (the
    /// Jacobian is set up at the iterate whose residual KINSOL just
    /// evaluated) keep the tree and the version().
    void
    set_displacement(const VectorType &U, const bool search = true);

    /// Changes whenever the node positions change: projections computed at
    /// the same version and slave position are still valid.
    std::uint64_t
    version() const
    {
      return positions_version;
    }

    /// Projection of the slave point @p x onto the pieces within 1.5 times
    /// the largest facet of it, or, where that finds none, within
    /// @p radius. The slave side passes 1.5 times its own facet size, so
    /// that a slave node that penetrates a finely meshed (thin) master by
    /// more than a master facet is still found.
    Projection
    project(const dealii::Point<dim> &x, const double radius = 0.) const;

    /// The projection of @p x onto piece @p piece alone, clamped to it (at
    /// its edge or node: the gap to the piece's tangent plane there); for a
    /// slave node held on one piece while its projection alternates
    /// between pieces that meet at a faceted corner.
    /// Beyond the end of the master: not in contact.
    Projection
    project_onto(const unsigned int piece, const dealii::Point<dim> &x) const;

    /// The gap of @p x to the vertex that pieces @p piece and @p partner
    /// share, along their mean normal n_v = (n_a + n_b) / |n_a + n_b|:
    /// g = (x - x_v) . n_v, symmetric in the two facets, each facet's
    /// normal n_a, n_b taken at x_v (from its end tangent there, for
    /// quadratic facets); for a slave node whose projection alternates
    /// between two faceted (f = 0) facets of a 2D master at a convex or
    /// concave vertex. Not found (failed) where the pieces are not two
    /// such facets sharing a node off any symmetry plane.
    Projection
    project_at_vertex(const unsigned int        piece,
                      const unsigned int        partner,
                      const dealii::Point<dim> &x) const;

    /// Linearization at projection @p p of the slave point @p x with slave
    /// DoFs @p slave_dofs.
    void
    linearize(
      const Projection                                       &p,
      const dealii::Point<dim>                               &x,
      const std::array<dealii::types::global_dof_index, dim> &slave_dofs,
      Linearization                                          &l) const;

    /// Master nodes that a slave point at @p x may couple to while it stays
    /// within @p radius of where it is (for the sparsity pattern).
    std::vector<unsigned int>
    nodes_near(const dealii::Point<dim> &x, const double radius) const;

    /// Master nodes whose positions enter projection @p p.
    std::vector<unsigned int>
    nodes_of(const Projection &p) const;

    /// Position and normal of piece @p piece at @p xi (current
    /// configuration).
    std::pair<dealii::Point<dim>, dealii::Tensor<1, dim>>
    evaluate(const unsigned int piece, const Xi &xi) const;

    /// The point of piece @p piece at @p xi, sum_j w_j y_j, linear in the
    /// node positions (y_j a node's position or its mirror image in a
    /// symmetry plane): per component of the point, the (DoF, weight)
    /// pairs, so that the point moves by sum weight * (the DoF's change).
    std::array<std::vector<std::pair<dealii::types::global_dof_index, double>>,
               dim>
    point_weights(const unsigned int piece, const Xi &xi) const;

    const std::vector<Node> &
    get_nodes() const
    {
      return nodes;
    }
    const std::vector<Facet> &
    get_facets() const
    {
      return facets;
    }
    /// Current node positions (set_displacement()).
    const std::vector<dealii::Point<dim>> &
    get_positions() const
    {
      return x;
    }
    /// Per node and component: does it carry XSYMM/YSYMM/ZSYMM?
    const std::vector<std::array<bool, dim>> &
    get_symmetry_flags() const
    {
      return on_symmetry_plane;
    }
    const std::vector<Piece> &
    get_pieces() const
    {
      return pieces;
    }
    /// The number of processes whose cells hold facets of the surface
    /// (every process holds all of them, gather(), unless distributed).
    unsigned int
    n_owners() const
    {
      return owners;
    }
    /// Largest facet diameter (reference configuration).
    double
    facet_size() const
    {
      return max_size;
    }
    unsigned int
    degree() const
    {
      return polynomial_degree;
    }

    /// Transition fraction at nodes between quadratic facets that do not
    /// kink (build_pieces_2d()): small enough that the load is passed to
    /// the facets' nodes within 4 f^2 = 0.16 % of their own proportions,
    /// large enough to keep the surface C1 when the master deforms.
    static constexpr double quadratic_fraction = 0.02;

  private:
    /// linearize() of a projection held at a vertex (project_at_vertex()).
    void
    linearize_at_vertex(
      const Projection                                       &p,
      const dealii::Point<dim>                               &x,
      const std::array<dealii::types::global_dof_index, dim> &slave_dofs,
      Linearization                                          &l) const;

    /// project() with candidates from the search tree within @p radius.
    Projection
    project_within(const dealii::Point<dim> &x, const double radius) const;

    /// Under MPI: replace this process's facets (of its own cells) by those
    /// of every process, with their @p diameters.
    void
    gather(const std::vector<double>        &diameters,
           const std::vector<std::uint64_t> &keys);
    /// Put the facets (with their @p ids and @p diameters) in the order of
    /// their ids, and the nodes in the order the facets first name them.
    void
    sort_canonically(std::vector<FacetId> &ids, std::vector<double> &diameters);
    /// Under MPI: the keys of this process's facets, from their @p ids and
    /// those of every process.
    std::vector<std::uint64_t>
    global_keys(const std::vector<FacetId> &ids) const;
    /// This process's facets with their @p keys, as numbers (per facet: its
    /// diameter, then per node its reference position; and its key, then
    /// per node its DoFs and symmetry flags).
    void
    pack(const std::vector<double>                    &diameters,
         const std::vector<std::uint64_t>             &keys,
         std::vector<double>                          &reals,
         std::vector<dealii::types::global_dof_index> &integers) const;
    /// Replace the facets by those of the packed lists @p parts, in the
    /// order of their keys, and rebuild pieces and smoothing.
    void
    unpack(
      const std::vector<std::pair<std::vector<double>,
                                  std::vector<dealii::types::global_dof_index>>>
        &parts);
    /// Pieces (2D) or neighbours and pieces (3D), the key map and the
    /// positions of the facets held.
    void
    build();
    void
    build_pieces_2d(const bool axisymmetric, const std::string &path);
    void
    build_neighbours_3d();

    template <typename T, typename Positions>
    void
    geometry(const Piece                             &piece,
             const std::array<T, dim - 1>            &xi,
             const Positions                         &pos,
             std::array<T, dim>                      &x,
             std::array<std::array<T, dim>, dim - 1> &a,
             std::array<T, dim>                      &n,
             std::vector<T>                          *weights) const;

    template <typename T, typename Positions>
    void
    blended_normal(const Piece                                   &piece,
                   const std::array<T, dim - 1>                  &xi,
                   const Positions                               &pos,
                   const std::array<std::array<T, dim>, dim - 1> &a,
                   std::array<T, dim>                            &n) const;

    template <typename T, typename Positions>
    std::array<T, dim>
    facet_normal(const unsigned int            facet,
                 const std::array<T, dim - 1> &xi,
                 const Positions              &pos) const;

    template <typename T, typename Positions>
    void
    residual(const Piece                  &piece,
             const std::array<T, dim - 1> &xi,
             const std::array<T, dim>     &xs,
             const Positions              &pos,
             std::array<T, dim - 1>       &R) const;

    Projection
    project_on(const unsigned int piece, const dealii::Point<dim> &x) const;
    /// Is the clamped projection @p p at a side of its piece beyond which
    /// there is no master (the end of a 2D chain, a 3D boundary edge)?
    bool
    beyond_end(const Projection &p) const;

    /// node_normal for the current positions (faceted masters).
    void
    update_node_normals();

    /// Nodes of the facets that share a node with @p facet (3D smoothing).
    std::vector<unsigned int>
    patch(const unsigned int facet) const;

    std::vector<Node>               nodes;
    std::vector<Facet>              facets;
    std::vector<Piece>              pieces;
    std::vector<dealii::Point<dim>> x; ///< current node positions
    std::uint64_t                   positions_version = 0;
    bool                            searchable = false; ///< tree built for x
    /// 3D: per facet corner (lexicographic), the (facet, corner) pairs of
    /// all facets at that node.
    std::vector<
      std::array<std::vector<std::pair<unsigned int, unsigned int>>, 4>>
      corners;
    /// Per node: does it carry XSYMM/YSYMM/ZSYMM (component a fixed on a
    /// symmetry plane)? In 3D the blended normal there lies in the plane.
    std::vector<std::array<bool, dim>> on_symmetry_plane;
    /// Faceted masters (f = 0): per node, the mean of the normals of the
    /// facets at it (current configuration; in a symmetry plane, as the
    /// mirrored surface would give), for Linearization::spring.
    std::vector<dealii::Tensor<1, dim>> node_normal;
    double                              fraction;
    double                              max_size          = 0.;
    unsigned int                        polynomial_degree = 1;
    unsigned int                        owners            = 1;
    std::uint64_t                       total_facets      = 0;
    bool                                axisymmetric      = false;
    std::string                         path;
    MPI_Comm                            comm = MPI_COMM_SELF;
    /// Distributed surfaces: this process's own facets, packed (pack()),
    /// their nodes' DoFs, and those DoFs' displacements at the last
    /// gather_near().
    std::vector<double>                          own_reals;
    std::vector<dealii::types::global_dof_index> own_integers;
    std::vector<dealii::types::global_dof_index> own_node_dofs;
    std::vector<double>                          own_gathered_at;
    /// piece_key() -> piece.
    std::map<std::uint64_t, unsigned int> piece_of_key;
    using Leaf = std::pair<dealii::BoundingBox<dim>, unsigned int>;
    dealii::RTree<Leaf> tree;
  };
} // namespace glide
