#include <glide/mechanics/rotation.h>
#include <glide/scene/input_error.h>

#include <deal.II/base/utilities.h>

#include <cmath>

namespace glide
{
  dealii::Tensor<1, 3>
  parse_rotation_axis(const std::string &text,
                      const unsigned int dim,
                      const std::string &parameter)
  {
    const auto parts = dealii::Utilities::split_string_list(text, ',');
    dealii::Tensor<1, 3> axis;
    bool                 numbers = parts.size() == 3;
    for (unsigned int d = 0; numbers && d < 3; ++d)
      {
        char        *end = nullptr;
        const double v   = std::strtod(parts[d].c_str(), &end);
        numbers = end && *end == '\0' && !parts[d].empty() && std::isfinite(v);
        axis[d] = v;
      }
    require(numbers,
            "Parameter '" + parameter + "' = '" + text +
              "' needs three comma-separated numbers, e.g. '0, 0, 1'.");
    require(axis.norm() > 0.,
            "Parameter '" + parameter + "' must not be the zero vector.");
    axis /= axis.norm();
    require(dim == 3 ||
              (std::abs(axis[0]) < 1e-12 && std::abs(axis[1]) < 1e-12),
            "Parameter '" + parameter + "' = '" + text +
              "': in a 2D scene rotations are in the plane, about z; use "
              "'0, 0, 1' (or '0, 0, -1').");
    return axis;
  }
} // namespace glide
