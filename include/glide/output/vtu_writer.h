#pragma once

#include <glide/mechanics/elasticity.h>
#include <glide/output/output_directory.h>

#include <string>
#include <utility>
#include <vector>

namespace glide
{
  /**
   * Writes one `.vtu` per output step and a `.pvd` collection (P5.1):
   * displacement, strain, stress (2x2 or 3x3 tensors plus the out-of-plane
   * or hoop component in 2D), von Mises stress, and material id. Each file
   * is written under a temporary name, checked and renamed when complete
   * (OutputDirectory); the `.pvd` is an index that commit_step() publishes
   * after the data it lists, so an interrupted run leaves only complete,
   * readable steps.
   */
  template <int dim>
  class VtuWriter
  {
  public:
    VtuWriter(const Elasticity<dim> &elasticity,
              OutputDirectory       &output,
              const std::string     &name);

    /// Collective: write the VTU of step @p step at load factor @p time
    /// under its final name (OutputError on every process if it fails).
    /// @p contact_force (same layout as U), if given, is written as the
    /// nodal vector field `contact_force`.
    void
    write(const unsigned int step,
          const double       time,
          const VectorType  &U,
          const VectorType  *contact_force = nullptr);

    /// Output points of the last write() where det F <= 0 (a strongly
    /// distorted cell's vertex at finite strain), whose stress fields
    /// were written as NaN; the same on every process.
    unsigned int
    inverted_points() const
    {
      return last_inverted;
    }

    /// Process 0, inside OutputDirectory::commit_step(): write the `.pvd`
    /// listing every VTU written so far.
    void
    write_pvd();

  private:
    unsigned int                                last_inverted = 0;
    const Elasticity<dim>                      &elasticity;
    OutputDirectory                            &output;
    const std::string                           name;
    std::vector<std::pair<double, std::string>> records;
  };
} // namespace glide
