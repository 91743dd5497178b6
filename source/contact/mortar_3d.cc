#include <glide/contact/mortar.h>

#include <Sacado.hpp>

namespace glide
{
  using namespace dealii;

  /// Mortar terms in 3D: not implemented yet (make_formulation() refuses
  /// mortar in 3D).
  template <int dim>
  template <typename T>
  void
  Mortar<dim>::compute_3d(const Patch &,
                          const std::vector<std::array<T, dim>> &,
                          const std::vector<std::array<T, dim>> &,
                          Terms<T> &) const
  {
    AssertThrow(false, ExcNotImplemented());
  }

  template void
  Mortar<3>::compute_3d<double>(const Patch &,
                                const std::vector<std::array<double, 3>> &,
                                const std::vector<std::array<double, 3>> &,
                                Terms<double> &) const;
  template void
  Mortar<3>::compute_3d<Sacado::Fad::DFad<double>>(
    const Patch &,
    const std::vector<std::array<Sacado::Fad::DFad<double>, 3>> &,
    const std::vector<std::array<Sacado::Fad::DFad<double>, 3>> &,
    Terms<Sacado::Fad::DFad<double>> &) const;
} // namespace glide
