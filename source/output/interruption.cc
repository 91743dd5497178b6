#include <glide/output/interruption.h>

#include <deal.II/base/mpi.h>

#include <signal.h>

#include <csignal>
#include <cstring>

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

    sigset_t
    stop_signals()
    {
      sigset_t set;
      sigemptyset(&set);
      sigaddset(&set, SIGTERM);
      sigaddset(&set, SIGINT);
      sigaddset(&set, SIGHUP);
      return set;
    }
  } // namespace

  Interrupted::Interrupted(const int signal_number)
    : std::runtime_error(
        std::string("stopped by signal ") +
        (signal_number == SIGTERM ? "SIGTERM" :
         signal_number == SIGINT  ? "SIGINT" :
         signal_number == SIGHUP  ? "SIGHUP" :
                                    std::to_string(signal_number)))
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
    for (const int s : {SIGTERM, SIGINT, SIGHUP})
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
