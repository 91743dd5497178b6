#include <glide/scene/input_error.h>

#include <deal.II/base/utilities.h>

#include <cmath>

namespace glide
{
  std::vector<double>
  read_numbers(const std::string &text,
               const std::string &path,
               const char         separator)
  {
    std::vector<double> numbers;
    for (const auto &piece :
         dealii::Utilities::split_string_list(text, separator))
      {
        double x = std::nan("");
        try
          {
            x = dealii::Utilities::string_to_double(piece);
          }
        catch (...)
          {}
        require(std::isfinite(x),
                "Parameter '" + path + "' = '" + text + "': cannot read '" +
                  piece +
                  "' as a number (a number's magnitude must lie between "
                  "about 2.3e-308 and 1.7e308, or be 0).");
        numbers.push_back(x);
      }
    return numbers;
  }
} // namespace glide
