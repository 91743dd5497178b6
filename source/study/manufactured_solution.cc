#include <glide/study/manufactured_solution.h>

#include <deal.II/base/numbers.h>

#include <cmath>

namespace glide
{
  using namespace dealii;

  namespace
  {
    constexpr double pi = numbers::PI;
    constexpr double A  = 0.01; // amplitude of g (axisymmetric)
    constexpr double B  = 0.02; // amplitude of w (axisymmetric)

    /// Values and derivatives of g(r, z) = A sin(pi z) cos(pi r / 2).
    struct G
    {
      double v, r, z, rr, rz, zz;
      G(const double x, const double y)
      {
        const double k = pi / 2;
        v              = A * std::sin(pi * y) * std::cos(k * x);
        r              = -A * k * std::sin(pi * y) * std::sin(k * x);
        z              = A * pi * std::cos(pi * y) * std::cos(k * x);
        rr             = -A * k * k * std::sin(pi * y) * std::cos(k * x);
        rz             = -A * k * pi * std::cos(pi * y) * std::sin(k * x);
        zz             = -A * pi * pi * std::sin(pi * y) * std::cos(k * x);
      }
    };

    /// Values and derivatives of w(r, z) = B cos(pi r) sin(pi z / 2), and
    /// w_r / r, which stays finite on the axis.
    struct W
    {
      double v, r, z, rr, rz, zz, r_over_r;
      W(const double x, const double y)
      {
        const double k = pi / 2;
        v              = B * std::cos(pi * x) * std::sin(k * y);
        r              = -B * pi * std::sin(pi * x) * std::sin(k * y);
        z              = B * k * std::cos(pi * x) * std::cos(k * y);
        rr             = -B * pi * pi * std::cos(pi * x) * std::sin(k * y);
        rz             = -B * pi * k * std::sin(pi * x) * std::cos(k * y);
        zz             = -B * k * k * std::cos(pi * x) * std::sin(k * y);
        const double sinc =
          (std::abs(pi * x) < 1e-8) ? 1. : std::sin(pi * x) / (pi * x);
        r_over_r = -B * pi * pi * sinc * std::sin(k * y);
      }
    };
  } // namespace

  template <int dim>
  ManufacturedSolution<dim>::ManufacturedSolution(const bool   axisymmetric,
                                                  const double lambda,
                                                  const double mu)
    : Function<dim>(dim)
    , axisymmetric(axisymmetric)
    , lambda(lambda)
    , mu(mu)
  {
    const double waves[3][3] = {{1.0, 0.5, 0.3},
                                {0.4, 1.2, 0.7},
                                {0.6, 0.2, 1.1}};
    for (unsigned int c = 0; c < 3; ++c)
      {
        for (unsigned int d = 0; d < dim; ++d)
          wave[c][d] = pi * waves[c][d];
        amplitude[c] = 0.01 * (1. + 0.5 * c);
        phase[c]     = 0.3 * (c + 1);
      }
  }

  template <int dim>
  double
  ManufacturedSolution<dim>::value(const Point<dim>  &p,
                                   const unsigned int c) const
  {
    if (axisymmetric)
      return c == 0 ? p[0] * G(p[0], p[1]).v : W(p[0], p[1]).v;
    return amplitude[c] * std::sin(wave[c] * p + phase[c]);
  }

  template <int dim>
  Tensor<1, dim>
  ManufacturedSolution<dim>::gradient(const Point<dim>  &p,
                                      const unsigned int c) const
  {
    Tensor<1, dim> g;
    if (axisymmetric)
      {
        if (c == 0)
          {
            const G gg(p[0], p[1]);
            g[0] = gg.v + p[0] * gg.r;
            g[1] = p[0] * gg.z;
          }
        else
          {
            const W w(p[0], p[1]);
            g[0] = w.r;
            g[1] = w.z;
          }
        return g;
      }
    return amplitude[c] * std::cos(wave[c] * p + phase[c]) * wave[c];
  }

  template <int dim>
  Tensor<2, dim>
  ManufacturedSolution<dim>::second_derivatives(const Point<dim>  &p,
                                                const unsigned int c) const
  {
    Tensor<2, dim> h;
    if (axisymmetric)
      {
        if (c == 0)
          {
            const G g(p[0], p[1]);
            h[0][0] = 2 * g.r + p[0] * g.rr;
            h[0][1] = h[1][0] = g.z + p[0] * g.rz;
            h[1][1]           = p[0] * g.zz;
          }
        else
          {
            const W w(p[0], p[1]);
            h[0][0] = w.rr;
            h[0][1] = h[1][0] = w.rz;
            h[1][1]           = w.zz;
          }
        return h;
      }
    return -amplitude[c] * std::sin(wave[c] * p + phase[c]) *
           outer_product(wave[c], wave[c]);
  }

  template <int dim>
  Tensor<1, dim>
  ManufacturedSolution<dim>::body_force(const Point<dim> &p) const
  {
    Tensor<1, dim> b;
    if (axisymmetric)
      {
        // Equilibrium in cylindrical coordinates without theta-dependence:
        //   d(s_rr)/dr + d(s_rz)/dz + (s_rr - s_tt)/r + b_r = 0,
        //   d(s_rz)/dr + d(s_zz)/dz + s_rz/r + b_z = 0,
        // written out for u_r = r g, u_z = w (see the class documentation).
        const G      g(p[0], p[1]);
        const W      w(p[0], p[1]);
        const double r = p[0];
        b[0]           = -(lambda * (3 * g.r + r * g.rr + w.rz) +
                 2 * mu * (2 * g.r + r * g.rr) + mu * (r * g.zz + w.rz) +
                 2 * mu * g.r);
        b[1]           = -(mu * (g.z + r * g.rz + w.rr) +
                 lambda * (2 * g.z + r * g.rz + w.zz) + 2 * mu * w.zz +
                 mu * (g.z + w.r_over_r));
        return b;
      }
    // div sigma_i = (lambda + mu) d_i (div u) + mu Laplace u_i
    Tensor<2, dim> H[dim];
    for (unsigned int c = 0; c < dim; ++c)
      H[c] = second_derivatives(p, c);
    for (unsigned int i = 0; i < dim; ++i)
      {
        double grad_div = 0, laplace = 0;
        for (unsigned int j = 0; j < dim; ++j)
          {
            grad_div += H[j][i][j];
            laplace += H[i][j][j];
          }
        b[i] = -((lambda + mu) * grad_div + mu * laplace);
      }
    return b;
  }

  template class ManufacturedSolution<2>;
  template class ManufacturedSolution<3>;
} // namespace glide
