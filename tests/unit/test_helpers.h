#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glide_test
{
  /// Write @p text to a fresh file @p name in a scratch directory under
  /// the system's temporary directory (never the source tree) and return
  /// its path. The directory is the running test's own: ctest runs the
  /// tests in parallel, and two tests writing the same file name would
  /// read each other's scenes.
  inline std::string
  write_file(const std::string &name, const std::string &text)
  {
    const ::testing::TestInfo *test =
      ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string test_name =
      test == nullptr ?
        std::string("outside-a-test") :
        std::string(test->test_suite_name()) + "." + test->name();
    const auto directory = std::filesystem::temp_directory_path() /
                           "glide-unit-tests" / test_name;
    std::filesystem::create_directories(directory);
    const std::string path = (directory / name).string();
    std::ofstream     out(path);
    out << text;
    return path;
  }
} // namespace glide_test

#include <glide/contact/contact.h>
#include <glide/mechanics/elasticity.h>

#include <random>

namespace glide_test
{
  /// Largest difference between J v and the central difference
  /// (F(U + h v) - F(U - h v)) / 2h of the contact residual over the
  /// unconstrained rows, and the largest entry of the latter: the contact
  /// Jacobian must be the derivative of the contact residual.
  template <int dim>
  std::pair<double, double>
  contact_jacobian_error(const glide::Elasticity<dim> &e,
                         glide::Contact<dim>          &contact,
                         const glide::VectorType      &U,
                         const glide::VectorType      &v,
                         const double                  h = 1e-7)
  {
    using namespace glide;
    // The exact derivative: without the Jacobian-only stabilization of
    // open nodes near the master (Contact::stabilization_weight()).
    contact.set_jacobian_stabilization(false);
    auto residual = [&](const VectorType &u, VectorType &F) {
      F = 0;
      contact.assemble(u, &F, nullptr);
    };
    MatrixType J;
    J.reinit(e.matrix_pattern());
    // The residual assembled alone (Linearization::derivatives false: a
    // formulation may skip the derivatives) equals the one assembled with
    // the Jacobian.
    VectorType F_alone(U), F_with_J(U);
    residual(U, F_alone);
    F_with_J = 0;
    contact.assemble(U, &F_with_J, &J);
    const double size = F_with_J.linfty_norm();
    F_with_J -= F_alone;
    EXPECT_LE(F_with_J.linfty_norm(), 1e-13 * size)
      << "the residual without derivatives differs from the one with them";
    J = 0;
    contact.assemble(U, nullptr, &J);
    VectorType Jv(U), Fp(U), Fm(U), Up(U), Um(U);
    J.vmult(Jv, v);
    Up.add(h, v);
    Um.add(-h, v);
    residual(Up, Fp);
    residual(Um, Fm);
    Fp -= Fm;
    Fp /= 2 * h;
    double err = 0, ref = 0;
    for (const auto i : e.locally_owned())
      if (!e.update_constraints().is_constrained(i))
        {
          err = std::max(err, std::abs(Jv[i] - Fp[i]));
          ref = std::max(ref, std::abs(Fp[i]));
        }
    contact.set_jacobian_stabilization(true);
    return {err, ref};
  }
} // namespace glide_test

namespace glide_test
{
  /// A random state (U) and direction (v) for a finite-difference check:
  /// displacements uniform in [-displacement, displacement], contact
  /// forces in [0, force], consistent with the constraints.
  template <int dim>
  void
  random_contact_state(const glide::Elasticity<dim> &e,
                       const glide::Contact<dim>    &contact,
                       glide::VectorType            &U,
                       glide::VectorType            &v,
                       const unsigned int            seed,
                       const double                  displacement,
                       const double                  force)
  {
    std::mt19937                           gen(seed);
    std::uniform_real_distribution<double> small(-displacement, displacement),
      positive(0., force);
    U.reinit(e.locally_owned(), MPI_COMM_WORLD);
    v.reinit(U);
    for (const auto i : e.displacement_owned())
      {
        U[i] = small(gen);
        v[i] = small(gen);
      }
    for (const auto i : contact.owned_multipliers())
      {
        U[i] = positive(gen);
        v[i] = positive(gen);
      }
    U.compress(dealii::VectorOperation::insert);
    v.compress(dealii::VectorOperation::insert);
    e.update_constraints().distribute(U);
    e.update_constraints().distribute(v);
  }
} // namespace glide_test

#include <deal.II/base/timer.h>

namespace glide_test
{
  /// A scene read from @p text (written to a scratch file @p name) with its
  /// bodies and contact pairs set up.
  template <int dim>
  struct ContactFixture
  {
    ContactFixture(const std::string &text, const std::string &name)
      : scene(glide::Scene::read(write_file(name, text)))
      , timer(MPI_COMM_WORLD,
              std::cout,
              dealii::TimerOutput::never,
              dealii::TimerOutput::wall_times)
      , e(scene, MPI_COMM_WORLD, timer)
      , contact(scene, e, MPI_COMM_WORLD)
    {
      e.setup();
      contact.setup(e.get_dof_handler().n_dofs());
      e.setup_system(contact.owned_multipliers(),
                     [&](dealii::DynamicSparsityPattern &dsp) {
                       contact.add_sparsity(dsp);
                     });
    }
    glide::Scene           scene;
    dealii::TimerOutput    timer;
    glide::Elasticity<dim> e;
    glide::Contact<dim>    contact;
  };

  /// The master surface made of surface @p surface of fixture @p s.
  template <int dim>
  std::unique_ptr<glide::MasterSurface<dim>>
  master_of(ContactFixture<dim> &s, const std::string &surface, const double f)
  {
    const auto ids = s.e.get_mesh().surface(surface, "test");
    return std::make_unique<glide::MasterSurface<dim>>(
      s.e,
      std::set<dealii::types::boundary_id>(ids.begin(), ids.end()),
      f,
      "test");
  }
} // namespace glide_test

namespace glide_test
{
  /// The contact Jacobian of fixture @p s at a random state (seed @p seed;
  /// displacements up to 0.01, forces up to 0.02) matches central finite
  /// differences to 1e-6 relative, with some slave nodes of the pair
  /// named `pair` closed; @p tag names the case in failure messages.
  template <int dim>
  void
  expect_consistent_jacobian(ContactFixture<dim> &s,
                             const std::string   &tag,
                             const unsigned int   seed)
  {
    glide::VectorType U, v;
    random_contact_state(s.e, s.contact, U, v, seed, 0.01, 0.02);
    s.contact.set_time(0.);
    ASSERT_FALSE(s.contact.needs_new_pattern(U)) << tag;
    const auto [err, ref] = contact_jacobian_error(s.e, s.contact, U, v, 1e-7);
    EXPECT_GT(ref, 0.) << tag;
    EXPECT_LT(err, 1e-6 * ref) << tag;
    const auto stats = s.contact.statistics(U);
    ASSERT_EQ(stats[0].first, "contact_pair_active");
    EXPECT_GT(std::stoi(stats[0].second), 0) << tag << ": some nodes closed";
  }
} // namespace glide_test
