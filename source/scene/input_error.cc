#include <glide/scene/input_error.h>
#include <glide/scene/text.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

namespace glide
{
  std::string
  printable_message(const std::string &message)
  {
    std::string out;
    out.reserve(message.size());
    for (const char c : message)
      {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 && c != '\n' && c != '\t')
          {
            static const char hex[] = "0123456789ABCDEF";
            out += "\\x";
            out += hex[u >> 4];
            out += hex[u & 15];
          }
        else if (u == 0x7f)
          out += "\\x7F";
        else
          out += c;
      }
    constexpr std::size_t longest = 4000, head = 3000, tail = 800;
    if (out.size() > longest)
      out = out.substr(0, head) + " [... " +
            std::to_string(out.size() - head - tail) +
            " characters left out ...] " + out.substr(out.size() - tail);
    return out;
  }

  std::string
  without_white_space(std::string text)
  {
    text.erase(std::remove_if(text.begin(),
                              text.end(),
                              [](const unsigned char c) {
                                return std::isspace(c);
                              }),
               text.end());
    return text;
  }

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
