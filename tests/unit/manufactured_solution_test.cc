// Unit test of the manufactured solution used by the convergence studies
// (P6.1). Why the expected answer is right: b = -div sigma(u) is checked
// against an independent computation, finite differences of the stress
// computed from the exact gradient, in plane strain, 3D and the
// cylindrical (axisymmetric) equilibrium equations. The axisymmetric
// solution must also be regular on the axis: u_r = 0 and du_z/dr = 0.
#include <glide/study/manufactured_solution.h>

#include <deal.II/base/numbers.h>

#include <gtest/gtest.h>

using namespace dealii;
using namespace glide;

namespace
{
  const double lambda = 1.3, mu = 0.7;

  /// Cauchy stress (3x3) of the exact solution at p.
  template <int dim>
  Tensor<2, 3>
  stress(const ManufacturedSolution<dim> &u,
         const Point<dim>                &p,
         const bool                       axisymmetric)
  {
    Tensor<2, 3> eps;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        eps[i][j] += 0.5 * (u.gradient(p, i)[j] + u.gradient(p, j)[i]);
    if (axisymmetric)
      eps[2][2] = u.value(p, 0) / p[0];
    Tensor<2, 3> s = 2 * mu * eps;
    for (unsigned int i = 0; i < 3; ++i)
      s[i][i] += lambda * trace(eps);
    return s;
  }

  template <int dim>
  void
  check(const bool axisymmetric, const Point<dim> &p)
  {
    ManufacturedSolution<dim> u(axisymmetric, lambda, mu);
    const double              h = 1e-5;
    Tensor<1, dim>            div;
    for (unsigned int j = 0; j < dim; ++j)
      {
        Point<dim> pp = p, pm = p;
        pp[j] += h;
        pm[j] -= h;
        const auto sp = stress(u, pp, axisymmetric),
                   sm = stress(u, pm, axisymmetric);
        for (unsigned int i = 0; i < dim; ++i)
          div[i] += (sp[i][j] - sm[i][j]) / (2 * h);
      }
    if (axisymmetric)
      {
        const auto s = stress(u, p, axisymmetric);
        div[0] += (s[0][0] - s[2][2]) / p[0];
        div[1] += s[0][1] / p[0];
      }
    const Tensor<1, dim> b = u.body_force(p);
    for (unsigned int i = 0; i < dim; ++i)
      EXPECT_NEAR(b[i], -div[i], 1e-7) << "component " << i;
  }
} // namespace

TEST(ManufacturedSolution, BodyForceBalancesStressPlaneStrain)
{
  check<2>(false, Point<2>(0.3, 0.7));
  check<2>(false, Point<2>(0.9, 0.1));
}

TEST(ManufacturedSolution, BodyForceBalancesStress3D)
{
  check<3>(false, Point<3>(0.3, 0.7, 0.2));
}

TEST(ManufacturedSolution, BodyForceBalancesStressAxisymmetric)
{
  check<2>(true, Point<2>(0.4, 0.6));
  check<2>(true, Point<2>(0.05, 0.3));
}

TEST(ManufacturedSolution, AxisymmetricSolutionIsRegularOnTheAxis)
{
  ManufacturedSolution<2> u(true, lambda, mu);
  EXPECT_EQ(u.value(Point<2>(0., 0.4), 0), 0.);
  EXPECT_NEAR(u.gradient(Point<2>(0., 0.4), 1)[0], 0., 1e-15);
  // The body force stays finite at the axis.
  EXPECT_TRUE(std::isfinite(u.body_force(Point<2>(0., 0.4))[1]));
}

TEST(ManufacturedSolution, GradientMatchesFiniteDifferences)
{
  ManufacturedSolution<3> u(false, lambda, mu);
  const Point<3>          p(0.2, 0.5, 0.8);
  const double            h = 1e-6;
  for (unsigned int c = 0; c < 3; ++c)
    for (unsigned int d = 0; d < 3; ++d)
      {
        Point<3> pp = p, pm = p;
        pp[d] += h;
        pm[d] -= h;
        EXPECT_NEAR(u.gradient(p, c)[d],
                    (u.value(pp, c) - u.value(pm, c)) / (2 * h),
                    1e-8);
      }
}
