#include <glide/contact/enforcement.h>

namespace glide
{
  using namespace dealii;

  namespace
  {
    /// The couplings between the displacements and the constraint: the
    /// force direction (column) and dg/du (row), their mean when
    /// symmetrized (R5.2); the displacement block -lambda dG/du (made
    /// symmetric when symmetrized).
    template <int dim>
    void
    displacement_block(const typename MasterSurface<dim>::Linearization &l,
                       const double                                      lambda,
                       const bool          symmetrized,
                       const double        stabilization,
                       Vector<double>     &column,
                       Vector<double>     &row,
                       Vector<double>     &rhs,
                       FullMatrix<double> &K)
    {
      const unsigned int m = l.dofs.size();
      for (unsigned int a = 0; a < m; ++a)
        {
          rhs(a) = -lambda * l.force(a);
          for (unsigned int b = 0; b < m; ++b)
            K(a, b) = -lambda * l.dforce(a, b);
        }
      column = l.force;
      row    = l.dgap;
      if (symmetrized)
        {
          for (unsigned int a = 0; a < m; ++a)
            for (unsigned int b = a + 1; b < m; ++b)
              K(a, b) = K(b, a) = 0.5 * (K(a, b) + K(b, a));
          column += l.dgap;
          column *= 0.5;
          row = column;
        }
      // Jacobian stabilization of open nodes near the master
      // (Contact::stabilization_weight(); the residual is untouched).
      // A faceted master gives a direction that does not jump at its
      // vertices (Linearization::spring).
      if (stabilization > 0.)
        {
          const Vector<double> &v = l.spring.size() == m ? l.spring : row;
          for (unsigned int a = 0; a < m; ++a)
            for (unsigned int b = 0; b < m; ++b)
              K(a, b) += stabilization * v(a) * v(b);
        }
    }

    /**
     * The local rows of a constraint with one multiplier (hard and
     * penalty): the displacement block, the force column -G, and the
     * multiplier row: closed, @p c times dg/du with the residual
     * @p closed_residual and the diagonal @p closed_diagonal; open (or
     * without a gap: beyond the master's end, no anchor, a failed
     * projection), C = lambda.
     */
    template <int dim>
    void
    multiplier_rows(const SlaveNode<dim>                             &node,
                    const Constraint<dim>                            &s,
                    const typename ContactEnforcement<dim>::Force    &f,
                    const typename MasterSurface<dim>::Linearization &l,
                    const bool                            symmetrized,
                    const double                          stabilization,
                    const double                          c,
                    const double                          closed_residual,
                    const double                          closed_diagonal,
                    std::vector<types::global_dof_index> &idx,
                    Vector<double>                       &rhs,
                    FullMatrix<double>                   &K)
    {
      if (!s.found())
        {
          idx.assign(1, node.multiplier);
          rhs.reinit(1);
          K.reinit(1, 1);
          rhs(0)  = f.lambda;
          K(0, 0) = 1.;
          return;
        }
      const unsigned int m = l.dofs.size();
      idx                  = l.dofs;
      idx.push_back(node.multiplier);
      rhs.reinit(m + 1);
      K.reinit(m + 1, m + 1);
      Vector<double> column, row;
      displacement_block<dim>(
        l, f.lambda, symmetrized, stabilization, column, row, rhs, K);
      rhs(m) = f.closed ? closed_residual : f.lambda;
      for (unsigned int a = 0; a < m; ++a)
        {
          K(a, m) = -column(a);
          K(m, a) = f.closed ? c * row(a) : 0.;
        }
      K(m, m) = f.closed ? closed_diagonal : 1.;
    }
  } // namespace

  template <int dim>
  typename ContactEnforcement<dim>::Force
  HardEnforcement<dim>::force(const SlaveNode<dim>  &node,
                              const Constraint<dim> &s,
                              const VectorType      &U) const
  {
    Force f;
    f.lambda = U[node.multiplier];
    // Active where lambda - c g >= 0: then C = c g (closed, g -> 0);
    // otherwise C = lambda (open, lambda -> 0).
    f.closed = s.found() && f.lambda - node.c * s.gap >= 0.;
    return f;
  }

  template <int dim>
  void
  HardEnforcement<dim>::local(const SlaveNode<dim>  &node,
                              const Constraint<dim> &s,
                              const Force           &f,
                              const Linearization   &l,
                              const bool             symmetrized,
                              const double           stabilization,
                              std::vector<types::global_dof_index> &idx,
                              Vector<double>                       &rhs,
                              FullMatrix<double>                   &K) const
  {
    multiplier_rows<dim>(node,
                         s,
                         f,
                         l,
                         symmetrized,
                         stabilization,
                         node.c,
                         node.c * l.gap,
                         0.,
                         idx,
                         rhs,
                         K);
  }

  template <int dim>
  typename ContactEnforcement<dim>::Force
  PenaltyEnforcement<dim>::force(const SlaveNode<dim>  &node,
                                 const Constraint<dim> &s,
                                 const VectorType      &U) const
  {
    Force f;
    f.lambda = U[node.multiplier];
    // Closed where lambda - c (g + lambda / k) >= 0: then C = c (g +
    // lambda / k) (lambda -> -k g); otherwise C = lambda (open).
    const double c = constant(node);
    f.closed = s.found() && f.lambda - c * (s.gap + f.lambda / node.k) >= 0.;
    return f;
  }

  template <int dim>
  void
  PenaltyEnforcement<dim>::local(const SlaveNode<dim>  &node,
                                 const Constraint<dim> &s,
                                 const Force           &f,
                                 const Linearization   &l,
                                 const bool             symmetrized,
                                 const double           stabilization,
                                 std::vector<types::global_dof_index> &idx,
                                 Vector<double>                       &rhs,
                                 FullMatrix<double>                   &K) const
  {
    const double c = constant(node);
    multiplier_rows<dim>(node,
                         s,
                         f,
                         l,
                         symmetrized,
                         stabilization,
                         c,
                         c * (l.gap + f.lambda / node.k),
                         c / node.k,
                         idx,
                         rhs,
                         K);
  }

  template <int dim>
  double
  PenaltyEnforcement<dim>::closing_multiplier(const SlaveNode<dim> &node,
                                              const double          gap) const
  {
    // lambda - c (g + lambda / k) >= 0 for g >= 0: lambda = c g / (1 - c /
    // k), with c <= k / 2; 1e-8 above it, so that round-off in force()
    // cannot put the node on the open branch (it did in the mm version of
    // a scene and not in the SI one: 5 against 2 iterations).
    const double c = constant(node);
    return (1. + 1e-8) * c * std::max(0., gap) / (1. - c / node.k);
  }

  template <int dim>
  double
  HardEnforcement<dim>::closing_multiplier(const SlaveNode<dim> &node,
                                           const double          gap) const
  {
    // lambda - c g >= 0: lambda = c g, 1e-8 above it, so that round-off in
    // force() cannot put the node on the open branch (as for penalty).
    return (1. + 1e-8) * node.c * std::max(0., gap);
  }

  template <int dim>
  std::unique_ptr<ContactEnforcement<dim>>
  make_enforcement(const ContactPairParameters &parameters)
  {
    if (parameters.enforcement == Enforcement::hard)
      return std::make_unique<HardEnforcement<dim>>();
    return std::make_unique<PenaltyEnforcement<dim>>();
  }

  template class HardEnforcement<2>;
  template class HardEnforcement<3>;
  template class PenaltyEnforcement<2>;
  template class PenaltyEnforcement<3>;
  template std::unique_ptr<ContactEnforcement<2>>
  make_enforcement<2>(const ContactPairParameters &);
  template std::unique_ptr<ContactEnforcement<3>>
  make_enforcement<3>(const ContactPairParameters &);
} // namespace glide
