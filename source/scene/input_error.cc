#include <glide/scene/input_error.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <filesystem>

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

  void
  require_regular_file(const std::string &file,
                       const std::string &what,
                       const std::string &advice)
  {
    std::error_code ec;
    const auto      status = std::filesystem::status(file, ec);
    require(!std::filesystem::exists(status) ||
              std::filesystem::is_regular_file(status),
            what + " '" + file + "' is " +
              (std::filesystem::is_directory(status) ?
                 std::string("a directory") :
                 std::string("not a regular file (a device such as "
                             "/dev/zero, a pipe or a socket)")) +
              "; " + advice);
  }
} // namespace glide
