#pragma once

#include <stdexcept>
#include <string>

namespace glide
{
  /**
   * An error in what the user gave glide: the scene file, a mesh file, a
   * command-line option. The message is meant for people: it names the file
   * or parameter path, says what is wrong and how to fix it. `main` prints it
   * once and exits with status 1; nothing is written before input is checked.
   */
  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /**
   * Throw an InputError with @p message unless @p condition holds. Unlike
   * deal.II's Assert, this check stays in release builds.
   */
  inline void
  require(const bool condition, const std::string &message)
  {
    if (!condition)
      throw InputError(message);
  }
} // namespace glide
