#pragma once

#include <mpi.h>

#include <string>

namespace glide
{
  /**
   * Collective: the first non-empty @p failure in rank order, on every
   * process; empty where no process failed. A process that meets an error
   * between two collective calls passes its message here instead of
   * throwing alone, so that every process throws the same error and none is
   * left waiting in the next collective call (issue 15).
   */
  std::string
  first_failure_on_any_process(const std::string &failure, MPI_Comm comm);

  /// Collective: throw @p Error with first_failure_on_any_process() on
  /// every process if any process failed.
  template <class Error>
  void
  throw_first_failure(const std::string &failure, MPI_Comm comm)
  {
    const std::string message = first_failure_on_any_process(failure, comm);
    if (!message.empty())
      throw Error(message);
  }
} // namespace glide
