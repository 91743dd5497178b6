#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace glide_test
{
  /// Write @p text to a fresh file @p name in a scratch directory under
  /// the system's temporary directory (never the source tree) and return
  /// its path.
  inline std::string
  write_file(const std::string &name, const std::string &text)
  {
    const auto directory =
      std::filesystem::temp_directory_path() / "glide-unit-tests";
    std::filesystem::create_directories(directory);
    const std::string path = (directory / name).string();
    std::ofstream     out(path);
    out << text;
    return path;
  }
} // namespace glide_test
