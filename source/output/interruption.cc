#include <glide/output/interruption.h>

#include <deal.II/base/mpi.h>

#include <semaphore.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>

namespace glide
{
  namespace
  {
    volatile std::sig_atomic_t last_signal = 0;

    /// Posted by the handler (sem_post is async-signal-safe); the watchdog
    /// waits on it.
    sem_t signalled;

    /// The watchdog's state, under its mutex: the StopDeferrals alive
    /// (output being written or published), whether the watchdog is ending
    /// the process (a new StopDeferral then waits for the end), whether it
    /// is disarmed (the run stopped at its check: its orderly end is not
    /// cut short), and the cleanup to run before the end with its owner.
    /// Allocated once and never freed, so that the detached thread never
    /// sees it destroyed at exit.
    struct WatchdogState
    {
      std::mutex            mutex;
      int                   deferrals = 0;
      bool                  ending    = false;
      bool                  disarmed  = false;
      std::function<void()> cleanup;
      const void           *cleanup_owner = nullptr;
    };

    WatchdogState &
    state()
    {
      static WatchdogState *const s = new WatchdogState;
      return *s;
    }

    extern "C" void
    record_signal(int signal_number)
    {
      last_signal = signal_number;
      sem_post(&signalled);
    }


    /// The signals that stop a run between load steps, with their names:
    /// a terminal's (SIGINT, SIGQUIT, SIGHUP), kill's default (SIGTERM),
    /// and those a batch system sends before it ends a job or that a
    /// limit raises: SIGUSR1 and SIGUSR2 (SLURM's --signal, PBS), SIGXCPU
    /// (a soft CPU time limit, ulimit -St), SIGALRM. Their default action ended
    /// glide in the middle of a file.
    constexpr std::pair<int, const char *> stops[] = {{SIGTERM, "SIGTERM"},
                                                      {SIGINT, "SIGINT"},
                                                      {SIGHUP, "SIGHUP"},
                                                      {SIGQUIT, "SIGQUIT"},
                                                      {SIGUSR1, "SIGUSR1"},
                                                      {SIGUSR2, "SIGUSR2"},
                                                      {SIGXCPU, "SIGXCPU"},
                                                      {SIGALRM, "SIGALRM"}};

    sigset_t
    stop_signals()
    {
      sigset_t set;
      sigemptyset(&set);
      for (const auto &[s, name] : stops)
        sigaddset(&set, s);
      return set;
    }

    std::string
    signal_name(const int signal_number)
    {
      for (const auto &[s, name] : stops)
        if (s == signal_number)
          return name;
      return std::to_string(signal_number);
    }

    /// Seconds a run has, after a stop signal, to reach its next check
    /// (GLIDE_STOP_GRACE, default 10); processes other than the leader
    /// wait twice as long and one second more, so that the leader, which
    /// writes the output, ends first and cleans up.
    double grace_seconds = 10.;

    /**
     * The run checks for a signal at each residual evaluation; a single
     * linear solve can take longer (MUMPS' analysis of a 2.5e6-DoF system
     * ignored SIGTERM for 14 minutes, beyond any batch system's grace
     * period). If the run has not stopped grace_seconds after the signal,
     * this thread ends the process at once with the signal's status: the
     * files of the completed steps are complete (each was renamed into
     * place when written), as after SIGKILL, and the step in progress is
     * lost, as it is when the run stops at its check.
     */
    void
    watchdog(const double grace)
    {
      while (sem_wait(&signalled) != 0)
        {}
      const auto                   start = std::chrono::steady_clock::now();
      auto                        &w     = state();
      std::unique_lock<std::mutex> lock(w.mutex);
      while (std::chrono::steady_clock::now() - start <
               std::chrono::duration<double>(grace) ||
             w.deferrals > 0 || w.disarmed)
        {
          lock.unlock();
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
          lock.lock();
        }
      // From here on no output starts (a new StopDeferral waits on the
      // mutex, held until the end).
      w.ending = true;
      if (w.cleanup)
        w.cleanup();
      const int          s = last_signal;
      std::ostringstream text;
      text << "glide: stopped by " << signal_name(s)
           << " at once: no safe point to stop at came within " << grace
           << " s of the signal (a long linear solve; GLIDE_STOP_GRACE sets "
              "the seconds); the results of the completed load steps are "
              "kept.\n";
      const std::string           message = text.str();
      [[maybe_unused]] const auto written =
        ::write(STDERR_FILENO, message.data(), message.size());
      _exit(128 + s);
    }
  } // namespace

  Interrupted::Interrupted(const int signal_number)
    : std::runtime_error("stopped by signal " + signal_name(signal_number))
    , signal_number(signal_number)
  {}

  void
  install_interrupt_handlers(const bool leader)
  {
    struct sigaction action;
    std::memset(&action, 0, sizeof(action));
    action.sa_handler = record_signal;
    sigemptyset(&action.sa_mask);
    // Restart interrupted system calls (writes): the run stops at its next
    // check, never in the middle of a file.
    action.sa_flags     = SA_RESTART;
    static bool started = false;
    if (!started)
      {
        if (const char *grace = std::getenv("GLIDE_STOP_GRACE"))
          {
            char        *end   = nullptr;
            const double value = std::strtod(grace, &end);
            if (end != grace && *end == '\0' && value >= 0. && value < 1e6)
              grace_seconds = value;
          }
        sem_init(&signalled, 0, 0);
        // The handlers run in the other threads: the watchdog starts with
        // the stop signals blocked.
        const sigset_t set = stop_signals();
        sigset_t       previous;
        pthread_sigmask(SIG_BLOCK, &set, &previous);
        std::thread(watchdog, leader ? grace_seconds : 2. * grace_seconds + 1.)
          .detach();
        pthread_sigmask(SIG_SETMASK, &previous, nullptr);
        started = true;
      }
    for (const auto &[s, name] : stops)
      sigaction(s, &action, nullptr);
  }

  int
  received_signal()
  {
    return last_signal;
  }

  void
  throw_if_interrupted(MPI_Comm comm)
  {
    const int s =
      dealii::Utilities::MPI::max(static_cast<int>(last_signal), comm);
    if (s != 0)
      {
        // Stopped at its check: the orderly end is not cut short.
        const std::lock_guard<std::mutex> lock(state().mutex);
        state().disarmed = true;
        throw Interrupted(s);
      }
  }

  SignalBlocker::SignalBlocker()
  {
    const sigset_t set = stop_signals();
    blocked            = (pthread_sigmask(SIG_BLOCK, &set, nullptr) == 0);
  }

  SignalBlocker::~SignalBlocker()
  {
    if (!blocked)
      return;
    const sigset_t set = stop_signals();
    pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  }

  void
  set_cleanup_at_once(const void *owner, std::function<void()> cleanup)
  {
    auto                             &w = state();
    const std::lock_guard<std::mutex> lock(w.mutex);
    w.cleanup       = std::move(cleanup);
    w.cleanup_owner = owner;
  }

  void
  clear_cleanup_at_once(const void *owner)
  {
    auto                             &w = state();
    const std::lock_guard<std::mutex> lock(w.mutex);
    if (w.cleanup_owner == owner)
      {
        w.cleanup       = {};
        w.cleanup_owner = nullptr;
      }
  }

  StopDeferral::StopDeferral()
  {
    auto                             &w = state();
    const std::lock_guard<std::mutex> lock(w.mutex);
    ++w.deferrals;
  }

  StopDeferral::~StopDeferral()
  {
    auto                             &w = state();
    const std::lock_guard<std::mutex> lock(w.mutex);
    --w.deferrals;
  }
} // namespace glide
