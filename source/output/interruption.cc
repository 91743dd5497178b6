#include <glide/output/interruption.h>

#include <deal.II/base/mpi.h>

#include <signal.h>

#include <csignal>
#include <cstring>
#include <string>
#include <utility>

namespace glide
{
  namespace
  {
    volatile std::sig_atomic_t last_signal = 0;

    extern "C" void
    record_signal(int signal_number)
    {
      last_signal = signal_number;
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
    action.sa_flags = SA_RESTART;
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
} // namespace glide
