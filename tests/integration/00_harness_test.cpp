// The test harness itself: whatever way a test ends, nothing it started outlives it. A test
// that aborts (a failed check inside a library, a crash) runs no destructor, so the processes it
// started must end with it by themselves.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>

#include "tests/support/child_process.hpp"
#include "tests/support/mosquitto.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

/// Whether `pid` still runs: a zombie nobody reaped (the machine's init may not) has ended.
bool running(pid_t pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string pid_field, command, state;
    if (!(stat >> pid_field >> command >> state)) return false;
    return state != "Z" && state != "X";
}

/// Forks a test process that starts what `start` starts, reports the pid on a pipe, and aborts
/// without running a destructor; returns that pid once the test process is gone.
template <typename Start>
pid_t pid_left_by_an_aborted_test(Start start) {
    int pipe_fds[2];
    EXPECT_EQ(::pipe(pipe_fds), 0);
    const pid_t test_process = ::fork();
    if (test_process == 0) {
        const pid_t child = start();
        (void)!::write(pipe_fds[1], &child, sizeof child);
        std::abort();
    }
    pid_t child = -1;
    EXPECT_EQ(::read(pipe_fds[0], &child, sizeof child), static_cast<ssize_t>(sizeof child));
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    int status = 0;
    ::waitpid(test_process, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status));
    return child;
}

/// Waits (bounded) for `pid` to end; kills it if it did not, so the check leaves nothing behind.
bool ends(pid_t pid) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (running(pid)) {
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(pid, SIGKILL);
            return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
}

TEST(Harness, AChildProcessEndsWithATestThatAborts) {
    const pid_t child = pid_left_by_an_aborted_test([] {
        auto* process = new ChildProcess({"/bin/sleep", "60"});  // never deleted: the abort
        return process->pid();
    });
    ASSERT_GT(child, 0);
    EXPECT_TRUE(ends(child)) << "sleep " << child << " outlived the test that started it";
}

TEST(Harness, AMosquittoEndsWithATestThatAborts) {
    const pid_t broker = pid_left_by_an_aborted_test([] {
        auto* mosquitto = new Mosquitto();  // never deleted: the abort
        return mosquitto->pid();
    });
    ASSERT_GT(broker, 0);
    EXPECT_TRUE(ends(broker)) << "mosquitto " << broker << " outlived the test that started it";
}

#ifndef NDEBUG
// Where assertions are on (Debug builds, the sanitizer flavour among them), nlohmann::json's
// would abort the test program on a key a message lacks, and every test after it with it.
TEST(Harness, AKeyAMessageLacksFailsOneTestInsteadOfAbortingTheProgram) {
    const auto message = nlohmann::json::parse(R"({"state":"ok"})");
    EXPECT_THROW(static_cast<void>(message["missing"]), std::logic_error);
}
#endif

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
