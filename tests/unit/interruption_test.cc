// The watchdog of a stop signal (interruption.h): a run that reaches no
// safe point within GLIDE_STOP_GRACE seconds of SIGTERM ends at once with
// status 143 (MUMPS' analysis of a large system ignored SIGTERM for 14
// minutes); one that stops in time ends as it chooses. Each case runs in a
// child process, which installs the handlers and receives the signal.
#include <glide/output/interruption.h>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <thread>

namespace
{
  /// Fork; the child sets the grace, installs the handlers, raises
  /// SIGTERM, then works for @p busy_seconds without checking and exits
  /// with status 0. Returns the child's wait status and the seconds it ran.
  std::pair<int, double>
  run_child(const char *grace, const double busy_seconds)
  {
    const auto  start = std::chrono::steady_clock::now();
    const pid_t pid   = fork();
    if (pid == 0)
      {
        setenv("GLIDE_STOP_GRACE", grace, 1);
        glide::install_interrupt_handlers();
        std::raise(SIGTERM);
        std::this_thread::sleep_for(
          std::chrono::duration<double>(busy_seconds));
        _exit(0);
      }
    int status = 0;
    waitpid(pid, &status, 0);
    return {status,
            std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                          start)
              .count()};
  }
} // namespace

TEST(Interruption, WatchdogEndsARunThatDoesNotStopInTime)
{
  // Grace 0.2 s, the child busy for 20 s: ended by the watchdog with
  // 128 + SIGTERM long before.
  const auto [status, seconds] = run_child("0.2", 20.);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_LT(seconds, 10.);
}

TEST(Interruption, WatchdogWaitsForItsGrace)
{
  // Grace 30 s, the child done after 0.3 s: its own exit status.
  const auto [status, seconds] = run_child("30", 0.3);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_LT(seconds, 25.);
}
