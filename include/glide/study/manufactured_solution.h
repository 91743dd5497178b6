#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/tensor.h>

namespace glide
{
  /**
   * A smooth manufactured displacement for convergence studies (P6.1),
   * with the body force that makes it an exact solution of small-strain
   * linear elasticity.
   *
   * Plane strain and 3D: u_c = A_c sin(a_c . x + phi_c).
   * Axisymmetric (x = r, y = z): u_r = r g(r, z) and u_z = w(r, z) with
   * g = A sin(pi z) cos(pi r / 2), w = B cos(pi r) sin(pi z / 2), chosen so
   * that u_r = 0 and du_z/dr = 0 on the axis, as a regular solid of
   * revolution requires. The body force is b = -div sigma with the
   * cylindrical divergence, evaluated from exact second derivatives.
   */
  template <int dim>
  class ManufacturedSolution : public dealii::Function<dim>
  {
  public:
    ManufacturedSolution(const bool   axisymmetric,
                         const double lambda,
                         const double mu);

    double
    value(const dealii::Point<dim> &p,
          const unsigned int        component) const override;

    dealii::Tensor<1, dim>
    gradient(const dealii::Point<dim> &p,
             const unsigned int        component) const override;

    /// Body force per unit volume that balances the exact stress.
    dealii::Tensor<1, dim>
    body_force(const dealii::Point<dim> &p) const;

    /// Second derivatives of component @p c.
    dealii::Tensor<2, dim>
    second_derivatives(const dealii::Point<dim> &p, const unsigned int c) const;

  private:
    const bool             axisymmetric;
    const double           lambda, mu;
    dealii::Tensor<1, dim> wave[3];
    double                 amplitude[3], phase[3];
  };
} // namespace glide
