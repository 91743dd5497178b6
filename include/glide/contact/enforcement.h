#pragma once

#include <glide/contact/formulation.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace glide
{
  /**
   * How the constraints of a pair are enforced (DESIGN.md, second
   * generation): the contact force of a constraint at an iterate and the
   * constraint's rows and columns of the residual and Jacobian. Hard
   * enforcement adds a block of block_size() multipliers per constraint
   * (the normal force now; friction adds dim - 1 tangential ones without a
   * redesign); penalty one (a perturbed Lagrangian).
   */
  template <int dim>
  class ContactEnforcement
  {
  public:
    using Linearization = typename MasterSurface<dim>::Linearization;

    /// The normal force of a constraint and whether it is closed.
    struct Force
    {
      double lambda = 0.;
      bool   closed = false;
    };

    virtual ~ContactEnforcement() = default;

    /// "hard" or "penalty".
    virtual std::string
    name() const = 0;

    /// Multipliers per constraint.
    virtual unsigned int
    block_size() const = 0;

    /// Whether a closed constraint's multiplier row keeps a diagonal
    /// entry (penalty: lambda + k dg = 0 in Newton, the multiplier known
    /// from the displacements), so that the linear solver can eliminate it
    /// whatever rows its force acts on (MultiplierCondensation).
    virtual bool
    compliant() const
    {
      return false;
    }

    /// The force of constraint @p s of node @p node at iterate @p U.
    virtual Force
    force(const SlaveNode<dim>  &node,
          const Constraint<dim> &s,
          const VectorType      &U) const = 0;

    /**
     * The constraint's local residual @p rhs and Jacobian @p K in the rows
     * and columns @p idx: the displacement DoFs of @p l (if s.found()),
     * then the node's multipliers. Displacement rows: -lambda G, G the
     * force direction, with Jacobian -lambda dG/du and the coupling with
     * the constraint; @p symmetrized uses the mean of G and dg/du on both
     * sides (R5.2); @p stabilization > 0 adds the Jacobian-only term
     * stabilization dg dg^T (Contact::stabilization_weight()).
     */
    virtual void
    local(const SlaveNode<dim>                         &node,
          const Constraint<dim>                        &s,
          const Force                                  &f,
          const Linearization                          &l,
          const bool                                    symmetrized,
          const double                                  stabilization,
          std::vector<dealii::types::global_dof_index> &idx,
          dealii::Vector<double>                       &rhs,
          dealii::FullMatrix<double>                   &K) const = 0;

    /// The multiplier that puts a node with gap @p gap (>= 0, small) on
    /// the closed branch of its complementarity function: the start of a
    /// pair's first contact (Contact::close_touching_nodes()).
    virtual double
    closing_multiplier(const SlaveNode<dim> &node, const double gap) const = 0;
  };

  /**
   * Hard contact: one multiplier lambda (the normal force) per constraint,
   * with the complementarity function
   *   C(lambda, g) = lambda - max(0, lambda - c g) = 0,
   * which holds exactly when lambda >= 0, g >= 0, lambda g = 0; c = E_pair
   * A / h makes c g a force, so rows and iteration counts do not depend on
   * units. Closed nodes end at g = 0 exactly, with no clearance: until
   * 2026-12-06 they were held at g_0 = 1e-10 times the scene size, which
   * took g_0 off every compression, so a light load's answer was wrong by
   * g_0 / (its compression), 1.4 % on the patch test at a strain of 1e-8
   * (scene.light_load_scales_linearly). A node touching the master at the
   * first contact is closed through its multiplier
   * (Contact::close_touching_nodes()), a body about to float is held by the
   * Jacobian's springs (Contact::set_jacobian_stabilization()).
   */
  template <int dim>
  class HardEnforcement : public ContactEnforcement<dim>
  {
  public:
    using typename ContactEnforcement<dim>::Force;
    using typename ContactEnforcement<dim>::Linearization;

    std::string
    name() const override
    {
      return "hard";
    }

    unsigned int
    block_size() const override
    {
      return 1;
    }

    Force
    force(const SlaveNode<dim>  &node,
          const Constraint<dim> &s,
          const VectorType      &U) const override;

    void
    local(const SlaveNode<dim>                         &node,
          const Constraint<dim>                        &s,
          const Force                                  &f,
          const Linearization                          &l,
          const bool                                    symmetrized,
          const double                                  stabilization,
          std::vector<dealii::types::global_dof_index> &idx,
          dealii::Vector<double>                       &rhs,
          dealii::FullMatrix<double>                   &K) const override;

    double
    closing_multiplier(const SlaveNode<dim> &node,
                       const double          gap) const override;
  };

  /**
   * Penalty contact: the force lambda = k max(0, -g), k the penalty
   * stiffness times the node's area (R4), solved as a perturbed Lagrangian
   * (Simo, Wriggers and Taylor 1985): one multiplier per constraint, as for
   * hard contact, with the complementarity function of the compliant gap
   * g + lambda / k,
   *   C(lambda, g) = lambda - max(0, lambda - c (g + lambda / k)) = 0,
   * which holds exactly when lambda = k max(0, -g): the answer is the
   * penalty method's. The multiplier carries the active set from one
   * iterate to the next as in hard contact (a closed node stays closed
   * while lambda > c (g + lambda / k)); decided by the gap alone, a node
   * whose penetration lambda / k (1e-3 of a facet's strain with the
   * default k) is below what one Newton step changes its gap by switched
   * in every iteration, and the default scene did not converge
   * (doc/theory/nonlinear-solution.md, "Penalty"). c = min(E_pair A / h,
   * k / 2).
   */
  template <int dim>
  class PenaltyEnforcement : public ContactEnforcement<dim>
  {
  public:
    using typename ContactEnforcement<dim>::Force;
    using typename ContactEnforcement<dim>::Linearization;

    std::string
    name() const override
    {
      return "penalty";
    }

    unsigned int
    block_size() const override
    {
      return 1;
    }

    bool
    compliant() const override
    {
      return true;
    }

    double
    closing_multiplier(const SlaveNode<dim> &node,
                       const double          gap) const override;

    Force
    force(const SlaveNode<dim>  &node,
          const Constraint<dim> &s,
          const VectorType      &U) const override;

    void
    local(const SlaveNode<dim>                         &node,
          const Constraint<dim>                        &s,
          const Force                                  &f,
          const Linearization                          &l,
          const bool                                    symmetrized,
          const double                                  stabilization,
          std::vector<dealii::types::global_dof_index> &idx,
          dealii::Vector<double>                       &rhs,
          dealii::FullMatrix<double>                   &K) const override;

  private:
    /// The complementarity constant c = min(E_pair A / h, k / 2).
    static double
    constant(const SlaveNode<dim> &node)
    {
      return std::min(node.c, 0.5 * node.k);
    }
  };

  /// The enforcement the pair's parameters name.
  template <int dim>
  std::unique_ptr<ContactEnforcement<dim>>
  make_enforcement(const ContactPairParameters &parameters);
} // namespace glide
