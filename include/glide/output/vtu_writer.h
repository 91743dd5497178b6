#pragma once

#include <glide/mechanics/elasticity.h>

#include <string>
#include <utility>
#include <vector>

namespace glide
{
  /**
   * Writes one `.vtu` per output step and a `.pvd` collection (P5.1):
   * displacement, strain, stress (2x2 or 3x3 tensors plus the out-of-plane
   * or hoop component in 2D), von Mises stress, and material id. Each file
   * is written under a temporary name and renamed when complete, and the
   * `.pvd` is rewritten the same way after each step, so an interrupted
   * run leaves only complete, readable steps.
   */
  template <int dim>
  class VtuWriter
  {
  public:
    VtuWriter(const Elasticity<dim> &elasticity,
              const std::string     &directory,
              const std::string     &name);

    /// Write step @p step at load factor @p time.
    void
    write(const unsigned int step, const double time, const VectorType &U);

  private:
    const Elasticity<dim>                      &elasticity;
    const std::string                           directory, name;
    std::vector<std::pair<double, std::string>> records;
  };
} // namespace glide
