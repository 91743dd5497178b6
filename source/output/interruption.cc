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

    /// SignalBlockers alive: the watchdog does not end the process while
    /// a step's indexes are being published.
    std::atomic<int> publishing{0};

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
    /// (GLIDE_STOP_GRACE, default 10).
    double grace_seconds = 10.;

    /// What to remove before the process ends at once (the output's
    /// staging directory and temporary files), under its mutex.
    std::mutex            cleanup_mutex;
    std::function<void()> cleanup_at_once;

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
    watchdog()
    {
      // The handlers run in the other threads.
      const sigset_t set = stop_signals();
      pthread_sigmask(SIG_BLOCK, &set, nullptr);
      while (sem_wait(&signalled) != 0)
        {}
      const auto start = std::chrono::steady_clock::now();
      while (std::chrono::steady_clock::now() - start <
               std::chrono::duration<double>(grace_seconds) ||
             publishing.load() > 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      {
        const std::lock_guard<std::mutex> lock(cleanup_mutex);
        if (cleanup_at_once)
          cleanup_at_once();
      }
      const int          s = last_signal;
      std::ostringstream text;
      text << "glide: stopped by " << signal_name(s)
           << " at once: no safe point to stop at came within " << grace_seconds
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
  install_interrupt_handlers()
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
        std::thread(watchdog).detach();
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
      throw Interrupted(s);
  }

  SignalBlocker::SignalBlocker()
  {
    ++publishing;
    const sigset_t set = stop_signals();
    blocked            = (pthread_sigmask(SIG_BLOCK, &set, nullptr) == 0);
  }

  SignalBlocker::~SignalBlocker()
  {
    --publishing;
    if (!blocked)
      return;
    const sigset_t set = stop_signals();
    pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  }

  void
  set_cleanup_at_once(std::function<void()> cleanup)
  {
    const std::lock_guard<std::mutex> lock(cleanup_mutex);
    cleanup_at_once = std::move(cleanup);
  }

  StopDeferral::StopDeferral()
  {
    ++publishing;
  }

  StopDeferral::~StopDeferral()
  {
    --publishing;
  }
} // namespace glide
