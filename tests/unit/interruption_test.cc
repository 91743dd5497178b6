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
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

namespace
{
  /// Fork; the child sets the grace, installs the handlers (and a cleanup
  /// that creates the file @p marker), raises SIGTERM, publishes output
  /// for @p deferred_seconds, then works for @p busy_seconds without
  /// checking and exits with status 0. Returns the child's wait status and
  /// the seconds it ran.
  std::pair<int, double>
  run_child(const char  *grace,
            const double busy_seconds,
            const double deferred_seconds = 0.,
            const char  *marker           = nullptr)
  {
    const auto  start = std::chrono::steady_clock::now();
    const pid_t pid   = fork();
    if (pid == 0)
      {
        setenv("GLIDE_STOP_GRACE", grace, 1);
        glide::install_interrupt_handlers();
        int owner = 0;
        if (marker != nullptr)
          glide::set_cleanup_at_once(&owner, [marker] {
            std::FILE *f = std::fopen(marker, "w");
            if (f != nullptr)
              std::fclose(f);
          });
        std::raise(SIGTERM);
        {
          // Output being published: the watchdog waits for its end.
          const glide::StopDeferral publishing;
          std::this_thread::sleep_for(
            std::chrono::duration<double>(deferred_seconds));
        }
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

TEST(Interruption, WatchdogWaitsForOutputAndRunsTheCleanup)
{
  // Grace 0.1 s, output published for 1.5 s after the signal: the watchdog
  // ends the child only after it (at least 1.5 s), and first runs the
  // cleanup, which leaves a marker file.
  const std::string marker = (std::filesystem::temp_directory_path() /
                              ("glide-watchdog-" + std::to_string(getpid())))
                               .string();
  std::filesystem::remove(marker);
  const auto [status, seconds] = run_child("0.1", 20., 1.5, marker.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  EXPECT_GE(seconds, 1.5);
  EXPECT_LT(seconds, 10.);
  EXPECT_TRUE(std::filesystem::exists(marker));
  std::filesystem::remove(marker);
}
