#pragma once

#include <glide/scene/input_error.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>

#include <cmath>
#include <sstream>
#include <string>

namespace glide
{
  /**
   * A function of the scene (boundary condition, body force, rigid motion)
   * parsed from its expression in x, y, (z,) t: a dealii::FunctionParser
   * that checks every value it returns. A value that is not a finite
   * number (a division by zero, the root or logarithm of a negative number,
   * an overflow) is an input error that names the parameter, the point and
   * the load factor, wherever the function is evaluated: glide never
   * computes with it. FunctionParser's vector_value() goes through value(),
   * so this one check sees every value.
   */
  template <int dim>
  class CheckedFunction : public dealii::FunctionParser<dim>
  {
  public:
    /// @p parameter and @p expression name the function in messages.
    CheckedFunction(const unsigned int n_components,
                    const std::string &parameter,
                    const std::string &expression)
      : dealii::FunctionParser<dim>(n_components)
      , parameter(parameter)
      , expression(expression)
    {}

    double
    value(const dealii::Point<dim> &p,
          const unsigned int        component = 0) const override
    {
      const double v = dealii::FunctionParser<dim>::value(p, component);
      if (!std::isfinite(v))
        {
          std::ostringstream s;
          s << "Parameter '" << parameter << "' = '" << expression << "'";
          if (this->n_components > 1)
            s << ": component " << component + 1;
          s << " evaluates to "
            << (std::isnan(v) ? "NaN" :
                v > 0         ? "+infinity" :
                                "-infinity")
            << " at (";
          for (unsigned int d = 0; d < dim; ++d)
            s << (d ? ", " : "") << p[d];
          s << "), t = " << this->get_time()
            << "; every value must be a finite number. Check the expression "
               "for a division by zero, the root or logarithm of a negative "
               "number, or an overflow at that point.";
          throw InputError(s.str());
        }
      return v;
    }

  private:
    const std::string parameter, expression;
  };
} // namespace glide
