#pragma once

#include <mpi.h>

#include <functional>
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

  /**
   * Install the handlers for the signals that stop a run (once, when the
   * load steps begin), and a watchdog thread: the run checks for a signal
   * at safe points, but one linear solve can outlast a batch system's grace
   * period (MUMPS ignored SIGTERM for 14 minutes on 2.5e6 DoFs). If the
   * run has not stopped GLIDE_STOP_GRACE seconds (default 10) after the
   * signal, and no StopDeferral is alive, the watchdog runs the cleanup of
   * set_cleanup_at_once() and ends the process at once with status 128 +
   * signal number: the completed steps' files stay, as after SIGKILL. A
   * run that stops at its check (throw_if_interrupted()) disarms it.
   * Processes other than the @p leader (MPI rank 0, which writes the
   * output) wait twice the grace and a second more, so that the leader
   * cleans up first.
   */
  void
  install_interrupt_handlers(const bool leader = true);

  /// What the watchdog runs before it ends the process at once, on behalf
  /// of @p owner; replaces the previous one.
  void
  set_cleanup_at_once(const void *owner, std::function<void()> cleanup);

  /// Remove the cleanup of @p owner, if it is the one set.
  void
  clear_cleanup_at_once(const void *owner);

  /// While one exists, the watchdog does not end the process (a step's
  /// files being published).
  class StopDeferral
  {
  public:
    StopDeferral();
    ~StopDeferral();
    StopDeferral(const StopDeferral &) = delete;
    StopDeferral &
    operator=(const StopDeferral &) = delete;
  };

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
