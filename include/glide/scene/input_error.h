#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace glide
{
  /**
   * An error in what the user gave glide: the scene file, a mesh file, a
   * command-line option. The message is meant for people: it names the file
   * or parameter path, says what is wrong and how to fix it. `main` prints it
   * once and exits with status 1; nothing is written before input is checked.
   */
  /**
   * @p message as it can be printed: control characters other than line
   * breaks and tabs shown as \xNN (a NUL byte read from a mesh file ended
   * the message there, and the newline after it was lost), and a message
   * longer than 4000 characters shortened in the middle, where the value
   * it quotes is (an 8 MB 'Function' was echoed whole), keeping its head
   * and the advice at its end.
   */
  std::string
  printable_message(const std::string &message);

  class InputError : public std::runtime_error
  {
  public:
    explicit InputError(const std::string &message)
      : std::runtime_error(printable_message(message))
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

  /**
   * The numbers of a list-valued parameter, e.g. a point '0, 1.5': the
   * @p text split at @p separator, each piece read as a finite double. A
   * piece that is not a number, or lies beyond double precision (1e-320,
   * 1e400), is an InputError naming the parameter @p path. An empty @p text
   * gives an empty list.
   */
  std::vector<double>
  read_numbers(const std::string &text,
               const std::string &path,
               const char         separator = ',');

  /**
   * Throw an InputError unless @p file, if it exists, is a regular file
   * (or a link to one): a device (/dev/zero), a pipe or a socket was read
   * until memory ran out, or forever. The message is @p what (e.g.
   * "Parameter 'Body b/Mesh file':"), the file, and @p advice. A missing
   * file passes: the caller's open reports it.
   */
  void
  require_regular_file(const std::string &file,
                       const std::string &what,
                       const std::string &advice);
} // namespace glide
