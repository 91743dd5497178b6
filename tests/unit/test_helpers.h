#pragma once

#include <cstdio>
#include <fstream>
#include <string>

namespace glide_test
{
  /// Write @p text to a fresh file in the test's working directory and
  /// return its name.
  inline std::string
  write_file(const std::string &name, const std::string &text)
  {
    std::ofstream out(name);
    out << text;
    return name;
  }
} // namespace glide_test
