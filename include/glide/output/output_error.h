#pragma once

#include <mpi.h>

#include <stdexcept>
#include <string>

namespace glide
{
  /**
   * An error while writing results or the log: a directory that cannot be
   * created, a full disk, a file that glide did not write where it would
   * write one, a closed standard output. The message names the file and
   * says what to do; `main` prints it once and exits with status 4. Every
   * file under its final name stays complete (see OutputDirectory).
   */
  class OutputError : public std::runtime_error
  {
  public:
    explicit OutputError(const std::string &message)
      : std::runtime_error(message)
    {}
  };

  /// What to tell the user about a failed write with the error code
  /// @p error (errno): its text and, for a full disk, the file size limit
  /// or a permission, what to do.
  std::string
  advice(const int error);

  /**
   * Collective: if @p failure is non-empty on any process, throw an
   * OutputError with the first such message on every process, so that no
   * process is left waiting in a later collective call (a process that
   * cannot create the output directory must not leave the others waiting
   * at a barrier).
   */
  void
  throw_output_error_on_any_process(const std::string &failure, MPI_Comm comm);
} // namespace glide
