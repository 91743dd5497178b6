#pragma once

#include <mpi.h>

#include <stdexcept>
#include <string>

namespace glide
{
  /**
   * SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGXCPU and SIGALRM
   * stop a run cleanly: the handler only records
   * the signal; the run checks for it at safe points (before each load step
   * and at each residual evaluation) and ends with an Interrupted exception,
   * after which `main` exits with status 128 + signal number, as a shell
   * reports a process killed by that signal. Output files are only ever
   * renamed to their final names when complete, and the indexes (.pvd files,
   * statistics.csv) are renamed together with these signals blocked (see
   * SignalBlocker), so an interrupted run leaves complete, consistent steps.
   */
  class Interrupted : public std::runtime_error
  {
  public:
    explicit Interrupted(const int signal_number);

    /// The signal that stopped the run.
    int signal_number;
  };

  /// Install the handlers for the signals that stop a run (once, when the
  /// load steps begin).
  void
  install_interrupt_handlers();

  /// The signal received so far on this process, 0 if none.
  int
  received_signal();

  /**
   * Collective: throw Interrupted on every process if any process has
   * received one of the signals. Call it only where every process calls it
   * the same number of times.
   */
  void
  throw_if_interrupted(MPI_Comm comm);

  /**
   * Blocks the signals that stop a run for its lifetime (a signal that
   * arrives meanwhile is delivered when it ends): the renames that publish
   * one step's indexes happen together.
   */
  class SignalBlocker
  {
  public:
    SignalBlocker();
    ~SignalBlocker();
    SignalBlocker(const SignalBlocker &) = delete;
    SignalBlocker &
    operator=(const SignalBlocker &) = delete;

  private:
    bool blocked = false;
  };
} // namespace glide
