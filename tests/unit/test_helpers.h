#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glide_test
{
  /// Write @p text to a fresh file @p name in a scratch directory under
  /// the system's temporary directory (never the source tree) and return
  /// its path.
  inline std::string
  write_file(const std::string &name, const std::string &text)
  {
    const auto directory =
      std::filesystem::temp_directory_path() / "glide-unit-tests";
    std::filesystem::create_directories(directory);
    const std::string path = (directory / name).string();
    std::ofstream     out(path);
    out << text;
    return path;
  }
} // namespace glide_test

#include <glide/contact/contact.h>
#include <glide/mechanics/elasticity.h>

namespace glide_test
{
  /// Largest difference between J v and the central difference
  /// (F(U + h v) - F(U - h v)) / 2h of the contact residual over the
  /// unconstrained rows, and the largest entry of the latter: the contact
  /// Jacobian must be the derivative of the contact residual.
  template <int dim>
  std::pair<double, double>
  contact_jacobian_error(const glide::Elasticity<dim> &e,
                         const glide::Contact<dim>    &contact,
                         const glide::VectorType      &U,
                         const glide::VectorType      &v,
                         const double                  h = 1e-7)
  {
    using namespace glide;
    auto residual = [&](const VectorType &u, VectorType &F) {
      F = 0;
      contact.assemble(u, &F, nullptr);
    };
    MatrixType J;
    J.reinit(e.matrix_pattern());
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
    return {err, ref};
  }
} // namespace glide_test
