#include <glide/material/material.h>
#include <glide/scene/input_error.h>

#include <iomanip>
#include <sstream>

namespace glide
{
  using namespace dealii;

  namespace
  {
    std::string
    short_number(const double x)
    {
      std::ostringstream s;
      s << std::setprecision(12) << x;
      return s.str();
    }
  } // namespace

  double
  MaterialParameters::lambda() const
  {
    return youngs_modulus * poissons_ratio /
           ((1. + poissons_ratio) * (1. - 2. * poissons_ratio));
  }

  double
  MaterialParameters::mu() const
  {
    return youngs_modulus / (2. * (1. + poissons_ratio));
  }

  void
  MaterialParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    prm.declare_entry("Young's modulus",
                      "1",
                      Patterns::Double(0.),
                      "Young's modulus E (stress units, e.g. Pa or MPa; "
                      "1e-100 <= E <= 1e100). Use the same unit system "
                      "throughout the scene; the moduli of the deformable "
                      "bodies may differ by a factor of 1e12 at most.");
    prm.declare_entry("Poisson's ratio",
                      "0.3",
                      Patterns::Double(-1., 0.5),
                      "Poisson's ratio nu, -0.9999 <= nu <= 0.4999 (nu = "
                      "0.5 is incompressible and not supported by this "
                      "displacement formulation; near it elements lock).");
    prm.leave_subsection();
  }

  void
  MaterialParameters::parse_parameters(ParameterHandler  &prm,
                                       const std::string &path)
  {
    prm.enter_subsection("Material");
    youngs_modulus = prm.get_double("Young's modulus");
    poissons_ratio = prm.get_double("Poisson's ratio");
    prm.leave_subsection();
    // 1e-100 <= E <= 1e100 in any unit system: stiffness entries (E times
    // lengths) and their products in the direct solver's factorization
    // must stay far inside double precision's range (1e+-308); outside it
    // the solve overflows into infinities and NaN.
    constexpr double smallest_modulus = 1e-100, largest_modulus = 1e100;
    require(youngs_modulus > 0.,
            "Parameter '" + path +
              "/Material/Young's modulus' must be greater than zero.");
    require(youngs_modulus >= smallest_modulus &&
              youngs_modulus <= largest_modulus,
            "Parameter '" + path +
              "/Material/Young's modulus' = " + short_number(youngs_modulus) +
              " is outside 1e-100 <= E <= 1e100, where the stiffness "
              "entries and their products in the solver overflow or "
              "underflow double precision. Choose units in which the "
              "moduli are moderate numbers (e.g. MPa and mm for steel: "
              "210000).");
    // nu = 0.5 is incompressible; lambda / mu = 2 nu / (1 - 2 nu) is about
    // 5000 at nu = 0.4999: beyond, displacement elements lock completely
    // and the Newton systems lose the digits the tolerance needs (the
    // load steps fail). Symmetrically, mu / K grows without bound as
    // nu -> -1.
    require(poissons_ratio >= -0.9999,
            "Parameter '" + path +
              "/Material/Poisson's ratio' = " + short_number(poissons_ratio) +
              " must satisfy -0.9999 <= nu <= 0.4999: at nu = -1 the bulk "
              "modulus is zero (the material offers no resistance to a "
              "change of volume) and the stiffness matrix is singular.");
    require(poissons_ratio <= 0.4999,
            "Parameter '" + path +
              "/Material/Poisson's ratio' = " + short_number(poissons_ratio) +
              " must satisfy -0.9999 <= nu <= 0.4999: closer to 0.5 the "
              "material is (nearly) incompressible, lambda/mu = 2 nu/(1 - "
              "2 nu) exceeds 5000, displacement elements lock and the "
              "solve fails; use for example 0.49 for rubber (this "
              "displacement formulation has no incompressible mode).");
  }



  LinearElastic::LinearElastic(const MaterialParameters &parameters)
    : lambda(parameters.lambda())
    , mu(parameters.mu())
  {}

  void
  LinearElastic::evaluate(const Tensor2 &grad_u, Tensor2 &out)
  {
    out    = tangent(grad_u);
    stress = out;
  }

  Tensor2
  LinearElastic::tangent(const Tensor2 &d) const
  {
    // C : sym(d) without forming the fourth-order tensor.
    Tensor2      s;
    const double tr = trace(d);
    for (unsigned int i = 0; i < 3; ++i)
      {
        for (unsigned int j = 0; j < 3; ++j)
          s[i][j] = mu * (d[i][j] + d[j][i]);
        s[i][i] += lambda * tr;
      }
    return s;
  }

  Tensor2
  LinearElastic::cauchy_stress() const
  {
    return stress;
  }



  NeoHookean::NeoHookean(const MaterialParameters &parameters)
    : lambda(parameters.lambda())
    , mu(parameters.mu())
  {}

  void
  NeoHookean::evaluate(const Tensor2 &grad_u, Tensor2 &out)
  {
    F = grad_u;
    for (unsigned int i = 0; i < 3; ++i)
      F[i][i] += 1.;
    J = determinant(F);
    if (!(J > 0.))
      throw std::runtime_error(
        "inverted element (det F = " + std::to_string(J) +
        " <= 0) in the neo-Hookean material: the load step is too large, or "
        "the mesh cannot follow the deformation there");
    log_J   = std::log(J);
    F_inv_T = transpose(invert(F));
    P       = mu * F + (lambda * log_J - mu) * F_inv_T;
    out     = P;
  }

  Tensor2
  NeoHookean::tangent(const Tensor2 &dF) const
  {
    const Tensor2 F_inv = transpose(F_inv_T);
    return mu * dF + lambda * trace(F_inv * dF) * F_inv_T +
           (mu - lambda * log_J) * (F_inv_T * transpose(dF) * F_inv_T);
  }

  Tensor2
  NeoHookean::cauchy_stress() const
  {
    // sigma = P F^T / J
    return (1. / J) * P * transpose(F);
  }



  std::unique_ptr<Material>
  create_material(const MaterialParameters &parameters,
                  const bool                geometric_nonlinearity)
  {
    if (geometric_nonlinearity)
      return std::make_unique<NeoHookean>(parameters);
    return std::make_unique<LinearElastic>(parameters);
  }
} // namespace glide
