// Unit tests of the constitutive laws (P1.2). Why the expected answers are
// right: the consistent tangent must equal the derivative of the stress,
// checked by central finite differences (error O(eps^2)); the neo-Hookean
// law must reduce to linear elasticity for infinitesimal strain, since
// both use the same Lame constants; an unstrained body carries no stress.
#include <glide/material/material.h>

#include <gtest/gtest.h>

using namespace glide;

namespace
{
  Tensor2
  sample_gradient(const double scale)
  {
    Tensor2      H;
    const double v[3][3] = {{0.11, -0.05, 0.02},
                            {0.07, -0.09, 0.04},
                            {-0.03, 0.06, 0.05}};
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        H[i][j] = scale * v[i][j];
    return H;
  }

  double
  tangent_fd_error(Material &law, const Tensor2 &H)
  {
    Tensor2 P;
    law.evaluate(H, P);
    double       worst = 0;
    const double eps   = 1e-6;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = 0; l < 3; ++l)
        {
          Tensor2 dH;
          dH[k][l] = 1.;
          law.evaluate(H, P);
          const Tensor2 analytic = law.tangent(dH);
          Tensor2       Pp, Pm;
          law.evaluate(H + eps * dH, Pp);
          law.evaluate(H - eps * dH, Pm);
          const Tensor2 fd = (Pp - Pm) / (2 * eps);
          worst = std::max(worst, (analytic - fd).norm() / (1. + fd.norm()));
        }
    return worst;
  }
} // namespace

TEST(Material, NeoHookeanTangentMatchesFiniteDifferences)
{
  MaterialParameters m;
  m.youngs_modulus = 210.;
  m.poissons_ratio = 0.3;
  NeoHookean law(m);
  EXPECT_LT(tangent_fd_error(law, sample_gradient(1.0)), 1e-7);
  EXPECT_LT(tangent_fd_error(law, sample_gradient(3.0)), 1e-7);
}

TEST(Material, LinearElasticTangentMatchesFiniteDifferences)
{
  MaterialParameters m;
  LinearElastic      law(m);
  EXPECT_LT(tangent_fd_error(law, sample_gradient(1.0)), 1e-8);
}

TEST(Material, NeoHookeanReducesToLinearElasticityForSmallStrain)
{
  MaterialParameters m;
  m.youngs_modulus = 5.;
  m.poissons_ratio = 0.25;
  NeoHookean    nh(m);
  LinearElastic le(m);
  const Tensor2 H = sample_gradient(1e-6);
  Tensor2       P_nh, P_le;
  nh.evaluate(H, P_nh);
  le.evaluate(H, P_le);
  // Difference is second order in the strain: O(1e-12) * E.
  EXPECT_LT((P_nh - P_le).norm(), 1e-10 * m.youngs_modulus);
  EXPECT_GT(P_le.norm(), 1e-7 * m.youngs_modulus);
}

TEST(Material, NoStressWithoutStrain)
{
  MaterialParameters m;
  NeoHookean         nh(m);
  Tensor2            P;
  nh.evaluate(Tensor2(), P);
  EXPECT_LT(P.norm(), 1e-14);
}

TEST(Material, InvertedElementIsReportedNotComputed)
{
  MaterialParameters m;
  NeoHookean         nh(m);
  Tensor2            H;
  H[0][0] = -2.; // F_00 = -1, det F < 0
  Tensor2 P;
  EXPECT_THROW(nh.evaluate(H, P), std::runtime_error);
}

TEST(Material, LameConstants)
{
  MaterialParameters m;
  m.youngs_modulus = 2.6;
  m.poissons_ratio = 0.3;
  EXPECT_NEAR(m.mu(), 1.0, 1e-14);
  EXPECT_NEAR(m.lambda(), 1.5, 1e-14);
}

TEST(Material, KinematicsChooseTheLaw)
{
  // P4.2: a geometrically linear scene gets the small-strain law, which
  // never forms F, J or F^{-1}; only a nonlinear scene gets neo-Hookean.
  MaterialParameters m;
  EXPECT_FALSE(create_material(m, false)->finite_strain());
  EXPECT_TRUE(create_material(m, true)->finite_strain());
  EXPECT_NE(dynamic_cast<LinearElastic *>(create_material(m, false).get()),
            nullptr);
}
