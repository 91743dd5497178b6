#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace glide
{
  /// Where and what a run writes.
  struct OutputParameters
  {
    /// Results go to `<directory>/<scene name>/`.
    std::string  directory = "output";
    bool         write_vtu = true;
    unsigned int every     = 1;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    void
    parse_parameters(dealii::ParameterHandler &prm);
  };
} // namespace glide
