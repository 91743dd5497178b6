#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>

namespace glide
{
  using Tensor2 = dealii::Tensor<2, 3>;

  /**
   * Elastic constants of one body. Which law uses them follows from the
   * scene's kinematics (P1.2): small-strain linear elasticity in a
   * geometrically linear scene, compressible neo-Hookean in a geometrically
   * nonlinear one. Both use the same Lame constants, so they agree for small
   * strains.
   */
  struct MaterialParameters
  {
    double youngs_modulus = 1.;
    double poissons_ratio = 0.3;

    double
    lambda() const;
    double
    mu() const;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm, const std::string &path);
  };

  /**
   * A constitutive law in the form the assembly needs. All quantities are
   * 3x3, whatever the analysis type: plane strain has zero out-of-plane
   * gradient, axisymmetric analysis puts the hoop term u_r/r in the (2,2)
   * entry. @p grad_u is the displacement gradient H; the law returns the
   * stress that is work-conjugate to H (the Cauchy stress for small strain,
   * the first Piola-Kirchhoff stress P for finite strain) and applies the
   * consistent tangent dP/dH to a direction.
   */
  class Material
  {
  public:
    virtual ~Material() = default;

    /// Evaluate the law at @p grad_u; must be called before tangent().
    virtual void
    evaluate(const Tensor2 &grad_u, Tensor2 &stress) = 0;

    /// Tangent at the last evaluated state applied to @p d_grad_u.
    virtual Tensor2
    tangent(const Tensor2 &d_grad_u) const = 0;

    /// Cauchy stress at the last evaluated state (for output).
    virtual Tensor2
    cauchy_stress() const = 0;

    /// True when the law is geometrically nonlinear.
    virtual bool
    finite_strain() const = 0;
  };

  /// Small-strain isotropic linear elasticity: sigma = lambda tr(eps) I +
  /// 2 mu eps with eps = sym(H). Never forms F.
  class LinearElastic : public Material
  {
  public:
    explicit LinearElastic(const MaterialParameters &parameters);
    void
    evaluate(const Tensor2 &grad_u, Tensor2 &stress) override;
    Tensor2
    tangent(const Tensor2 &d_grad_u) const override;
    Tensor2
    cauchy_stress() const override;
    bool
    finite_strain() const override
    {
      return false;
    }

  private:
    const double lambda, mu;
    Tensor2      stress;
  };

  /**
   * Compressible neo-Hookean material with strain energy
   * W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2,
   * P = mu F + (lambda ln J - mu) F^{-T},
   * dP[dF] = mu dF + lambda tr(F^{-1} dF) F^{-T}
   *          + (mu - lambda ln J) F^{-T} dF^T F^{-T}.
   */
  class NeoHookean : public Material
  {
  public:
    explicit NeoHookean(const MaterialParameters &parameters);
    void
    evaluate(const Tensor2 &grad_u, Tensor2 &stress) override;
    Tensor2
    tangent(const Tensor2 &d_grad_u) const override;
    Tensor2
    cauchy_stress() const override;
    bool
    finite_strain() const override
    {
      return true;
    }

    /// Determinant of F at the last evaluated state.
    double
    jacobian() const
    {
      return J;
    }

  private:
    const double lambda, mu;
    Tensor2      F, F_inv_T, P;
    double       J = 1., log_J = 0.;
  };

  /// The law for a body: linear elastic or neo-Hookean.
  std::unique_ptr<Material>
  create_material(const MaterialParameters &parameters,
                  const bool                geometric_nonlinearity);
} // namespace glide
