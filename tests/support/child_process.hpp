#pragma once
/// Runs a program (usually the real eip2mqtt binary) as a child process with its stderr and
/// stdout captured to a file, for integration tests.

#include <sys/types.h>

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace eip2mqtt::test {

class ChildProcess {
public:
    /// Starts argv[0] with the given arguments; `env` entries are added to the environment.
    explicit ChildProcess(std::vector<std::string> argv,
                          std::map<std::string, std::string> env = {});
    /// Kills the child with SIGKILL if it is still running.
    ~ChildProcess();
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    pid_t pid() const { return pid_; }
    void signal(int signo);
    /// Waits for the exit; the exit status (128 + signal when killed), or nullopt on timeout.
    std::optional<int> wait(std::chrono::milliseconds timeout);
    bool running();
    /// Everything the child wrote to stdout and stderr so far.
    std::string output() const;
    /// Waits until output() contains `text`; false after `timeout`.
    bool wait_for_output(const std::string& text,
                         std::chrono::milliseconds timeout = std::chrono::seconds(10));

private:
    pid_t pid_ = -1;
    std::optional<int> status_;
    std::string output_file_;
};

/// Called in a child between fork() and exec(): the child is killed when the test process
/// ends, however it ends (a failed assertion that aborts, a crash, a timeout's SIGKILL), so a
/// test never leaves a gateway or a broker running behind it. `parent` is the test process's
/// pid, read before the fork. Children must be forked from a thread that outlives them (the
/// kernel sends the signal when the forking thread ends): the tests' main thread.
void end_with_parent(pid_t parent);

/// Runs a command to completion (bounded by `timeout`); returns exit status and output.
struct RunResult {
    int status = -1;
    std::string output;
};
RunResult run_command(std::vector<std::string> argv, std::chrono::milliseconds timeout);

/// The shared libraries `binary` names (DT_NEEDED, by readelf): the dynamic loader maps each at
/// start.
std::vector<std::string> needed_libraries(const std::string& binary);

}  // namespace eip2mqtt::test
