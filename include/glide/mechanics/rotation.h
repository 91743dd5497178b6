#pragma once

#include <deal.II/base/tensor.h>

#include <array>
#include <string>

namespace glide
{
  /**
   * A prescribed rigid rotation's axis (P1.4): the unit vector of the
   * parameter @p parameter, three comma-separated components. In 2D the
   * axis must be z (rotations in the plane); a zero or malformed axis is an
   * input error that names the parameter.
   */
  dealii::Tensor<1, 3>
  parse_rotation_axis(const std::string &text,
                      const unsigned int dim,
                      const std::string &parameter);

  /**
   * @p v turned by @p theta (radians, right-hand rule) about the unit axis
   * @p axis through the origin (Rodrigues' formula); in 2D about z.
   */
  template <int dim>
  dealii::Tensor<1, dim>
  rotate(const dealii::Tensor<1, dim> &v,
         const dealii::Tensor<1, 3>   &axis,
         const double                  theta)
  {
    dealii::Tensor<1, 3> w;
    for (unsigned int d = 0; d < dim; ++d)
      w[d] = v[d];
    const double         c = std::cos(theta), s = std::sin(theta);
    dealii::Tensor<1, 3> r = c * w + s * dealii::cross_product_3d(axis, w) +
                             (1. - c) * (axis * w) * axis;
    dealii::Tensor<1, dim> result;
    for (unsigned int d = 0; d < dim; ++d)
      result[d] = r[d];
    return result;
  }
} // namespace glide
