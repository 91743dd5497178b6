#pragma once

#include <glide/contact/formulation.h>

#include <deal.II/base/bounding_box.h>
#include <deal.II/numerics/rtree.h>

#include <memory>
#include <string>
#include <vector>

namespace glide
{
  /**
   * Mortar contact, finite sliding (R14; doc/theory/mortar.md): the
   * contact conditions hold in a weighted-integral sense over the slave
   * surface, with dual Lagrange multipliers (Wohlmuth; Popp, Gee and Wall
   * 2009). One constraint per slave node j:
   *
   *   weighted gap  g~_j = int_{Gamma_s} Phi_j g dA,
   *   g = n(xi) . (x_m(chi(xi)) - x_s(xi)),
   *
   * with Phi_j the dual basis function of node j, n the continuous slave
   * normal field (interpolated from averaged nodal normals) and chi(xi)
   * the master point on the line through x_s(xi) along n. The integral
   * is taken segment by segment (2D): the slave facet is cut at the
   * projections of the master nodes, and each piece is integrated with a
   * five-point Gauss rule, which is exact for the polynomial integrands
   * of a flat interface (R14.2).
   *
   * The dual basis is biorthogonal on the part of the slave facet that the
   * master covers ("consistent" dual basis; Cichosz and Bischoff 2011):
   * Phi_j = sum_l A_jl N_l with A = D M^{-1}, D = diag(int N_k dA), M =
   * int N_k N_l dA over the covered part. So the slave mortar matrix is
   * diagonal, D_jj = int_cov N_j dA, and the constraint is enforced on
   *
   *   g_j = g~_j / D_jj   (a length: COPEN),
   *
   * with the multiplier L_j = D_jj lambda_j a nodal force whose
   * virtual work is L_j n_j . (delta x_j - sum_m (M_jm / D_jj) delta
   * x_m), M_jm = int_cov Phi_j N_m dA the mortar matrix of the master.
   * The enforcement (hard NCP, penalty) is that of node to surface. Each
   * L_j enters only the rows of its own slave node and of the master, so
   * the multipliers could be condensed node by node; they are not yet
   * (they stay unknowns of KINSOL, doc/theory/mortar.md).
   *
   * Linearization: automatic differentiation (Sacado) through the whole
   * computation (nodal normals, segment ends, projections of the Gauss
   * points, dual basis), with the projections converged in double and
   * finished by one Newton step in the differentiated type, which gives
   * the exact first derivatives (R14.4).
   *
   * Implemented for 2D (plane strain, axisymmetric) and facets of degree
   * 1 and 2 (R14.7: the dual basis of a quadratic line exists, since all
   * its int N_k are positive), and for 3D with bilinear quadrilateral
   * facets (compute_3d(), source/contact/mortar_3d.cc: clipping in the
   * slave facet's auxiliary plane, Popp, Gitterle, Gee and Wall 2010);
   * degree 2 in 3D is refused by make_formulation().
   *
   * A locally refined slave surface: a hanging node h (u_h = sum_p w_hp
   * u_p) has no multiplier of its own; its terms are added to its
   * parents' with the constraint's weights (D_p += w_hp D_h, g~_p +=
   * w_hp g~_h, M_pm += w_hp M_hm; SlaveNode::hanging). The multiplier
   * space is then spanned by Phi_p + sum_h w_hp Phi_h, dual to the
   * constrained shape functions up to the D_h of the hanging nodes, and
   * the force L_p acts on node p: a uniform pressure still gives the
   * exact nodal forces on both sides.
   */
  template <int dim>
  class Mortar : public Formulation<dim>
  {
  public:
    using typename Formulation<dim>::Linearization;

    Mortar(const PairContext<dim>             &context,
           std::unique_ptr<MasterSurface<dim>> surface);

    std::string
    name() const override
    {
      return "mortar, finite sliding";
    }

    void
    setup(const std::vector<SlaveNode<dim>> &nodes) override;

    void
    move(const VectorType &U) const override;
    /// The master's nodes and those of the slave facets (a node's weighted
    /// gap integrates over the facets around it, across processes).
    void
    read_dofs(
      std::vector<dealii::types::global_dof_index> &dofs) const override;

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

    bool
    slides() const override
    {
      return true;
    }

    void
    commit_step(const VectorType                   &U,
                const std::vector<Constraint<dim>> &s,
                const std::vector<bool>            &closed,
                const double                        t_old,
                const double                        t_new) override;

    /// The mortar terms of slave node j at the current iterate: D_jj, the
    /// weighted gap g~_j, the nodal normal n_j and M_jm for the master
    /// nodes m (indices into the master surface's nodes).
    template <typename T>
    struct Terms
    {
      T                         weight       = 0.;
      T                         weighted_gap = 0.;
      std::array<T, dim>        normal;
      std::vector<unsigned int> master_nodes;
      std::vector<T>            M;
      /// A segment end or Gauss point whose projection did not converge.
      bool failed = false;
    };

    /// The terms of node @p i at the current positions (move()), in double.
    Terms<double>
    terms(const unsigned int i) const;

  protected:
    /// The memo of facet pairs refers to the old master facets; the search
    /// tree follows version().
    void
    renumber_pieces(const std::vector<std::uint64_t> &) override
    {
      pair_cache.reset();
    }

  private:
    /// The slave and master nodes and the master facets that enter the
    /// terms of one slave node at the current positions.
    struct Patch
    {
      std::vector<unsigned int> slave;  ///< slave surface nodes, j first
      std::vector<unsigned int> facets; ///< slave facets at j
      /// Per slave facet: candidate master facets.
      std::vector<std::vector<unsigned int>> candidates;
      std::vector<unsigned int>              master; ///< their nodes
    };

    /// The patch of slave surface node @p j.
    Patch
    patch_at(const unsigned int j) const;

    /// The patches of slave node @p i: its own first, then those of the
    /// hanging nodes merged into it (members).
    std::vector<Patch>
    patches(const unsigned int i) const;

    /// Add @p w times the terms @p t of one patch to @p sum, whose
    /// master_nodes hold every master node of the patches (the normal is
    /// that of the first patch, @p first).
    template <typename T>
    void
    add_weighted(const Terms<T> &t,
                 const double    w,
                 const bool      first,
                 Terms<T>       &sum) const;

    /// The terms of the patch @p p with slave positions @p xs (per
    /// p.slave) and master positions @p xm (per p.master).
    template <typename T>
    void
    compute(const Patch                           &p,
            const std::vector<std::array<T, dim>> &xs,
            const std::vector<std::array<T, dim>> &xm,
            Terms<T>                              &terms) const;

    /// compute() in 3D (source/contact/mortar_3d.cc).
    template <typename T>
    void
    compute_3d(const Patch                           &p,
               const std::vector<std::array<T, dim>> &xs,
               const std::vector<std::array<T, dim>> &xm,
               Terms<T>                              &terms) const;

    /// 3D: whether master facet @p master faces slave facet @p facet and
    /// overlaps it in its auxiliary plane at the current positions (the
    /// test of compute_3d(), on the values; source/contact/mortar_3d.cc).
    bool
    overlaps_3d(const unsigned int facet, const unsigned int master) const;

    /// Master facets whose current bounding box comes within @p radius of
    /// that of slave facet @p facet.
    std::vector<unsigned int>
    candidates(const unsigned int facet, const double radius) const;

    /// The slave surface: its facets and nodes (the extraction of the
    /// master surface, reused).
    std::unique_ptr<MasterSurface<dim>> slave;
    /// Slave surface node -> index into the formulation's slave nodes.
    std::vector<unsigned int> node_of;
    /// Formulation's slave node -> slave surface node.
    std::vector<unsigned int> surface_node;
    /// Per slave node: the slave surface nodes whose terms it sums, with
    /// their weights (itself with 1 first, then its hanging nodes).
    std::vector<std::vector<std::pair<unsigned int, double>>> members;
    /// Slave surface node -> the slave facets at it.
    std::vector<std::vector<unsigned int>> facets_at;
    /// Per slave facet: the search radius around it.
    std::vector<double> radius;
    /// Current positions of the slave surface's nodes, and the search tree
    /// of the master facets' bounding boxes (a function of U, rebuilt when
    /// the master moved).
    mutable std::vector<dealii::Point<dim>> slave_x;
    using Leaf = std::pair<dealii::BoundingBox<dim>, unsigned int>;
    mutable dealii::RTree<Leaf> tree;
    mutable std::uint64_t       tree_version =
      std::numeric_limits<std::uint64_t>::max();
    /// Memo of the integrals of slave-master facet pairs in 3D (defined in
    /// source/contact/mortar_3d.cc): the patches of a slave facet's four
    /// nodes integrate the same pairs. An entry is used only where the
    /// pair's coordinates and normals are those it was computed with, so a
    /// hit gives what the computation would, bit for bit. Not for
    /// concurrent use (Contact::assemble() evaluates nodes one at a time).
    struct PairCache;
    mutable std::shared_ptr<PairCache> pair_cache;
    /// Per node: master nodes coupled in the sparsity pattern (sorted).
    std::vector<std::vector<unsigned int>> coupled;
    /// Per node, at the end of the last converged step: position, and the
    /// mortar point sum_m (M_jm / D_jj) x_m as a point of the master's
    /// material (for the slip, R12: the slave node's motion relative to
    /// the master's material under it). Its DoFs are read through
    /// read_dofs(), so under MPI it moves with the master also where this
    /// process no longer holds the facets.
    std::vector<dealii::Point<dim>> previous_position;
    std::vector<MaterialPoint<dim>> previous_point;
    std::vector<bool>               previous_found;
  };
} // namespace glide
