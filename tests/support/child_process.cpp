#include "tests/support/child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace eip2mqtt::test {
namespace {

using Clock = std::chrono::steady_clock;

// Polling interval for child exit and output: waitpid has no timeout, so wait() polls it.
constexpr auto poll_interval = std::chrono::milliseconds(5);

std::string temp_output_file() {
    char name[] = "/tmp/eip2mqtt-child-XXXXXX";
    const int fd = ::mkstemp(name);
    if (fd < 0) throw std::runtime_error("mkstemp failed");
    ::close(fd);
    return name;
}

int decode_status(int status) {
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
    return -1;
}

}  // namespace

void end_with_parent(pid_t parent) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    // The parent may have ended before the line above: then nobody would send the signal.
    if (::getppid() != parent) ::_exit(127);
}

ChildProcess::ChildProcess(std::vector<std::string> argv, std::map<std::string, std::string> env)
    : output_file_(temp_output_file()) {
    const pid_t parent = ::getpid();
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
        end_with_parent(parent);
        const int fd = ::open(output_file_.c_str(), O_WRONLY | O_TRUNC);
        ::dup2(fd, STDOUT_FILENO);
        ::dup2(fd, STDERR_FILENO);
        const int null = ::open("/dev/null", O_RDONLY);
        ::dup2(null, STDIN_FILENO);
        for (const auto& [key, value] : env) ::setenv(key.c_str(), value.c_str(), 1);
        std::vector<char*> args;
        for (auto& arg : argv) args.push_back(arg.data());
        args.push_back(nullptr);
        ::execv(args[0], args.data());
        ::_exit(127);
    }
}

ChildProcess::~ChildProcess() {
    if (running()) {
        ::kill(pid_, SIGKILL);
        int status = 0;
        ::waitpid(pid_, &status, 0);
    }
    ::unlink(output_file_.c_str());
}

void ChildProcess::signal(int signo) {
    if (!status_) ::kill(pid_, signo);
}

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!status_) {
        int status = 0;
        const pid_t r = ::waitpid(pid_, &status, WNOHANG);
        if (r == pid_) {
            status_ = decode_status(status);
            break;
        }
        if (Clock::now() >= deadline) return std::nullopt;
        std::this_thread::sleep_for(poll_interval);
    }
    return status_;
}

bool ChildProcess::running() { return !wait(std::chrono::milliseconds(0)).has_value(); }

std::string ChildProcess::output() const {
    std::ifstream file(output_file_);
    std::stringstream buffer;
    buffer << file.rdbuf();
    return buffer.str();
}

bool ChildProcess::wait_for_output(const std::string& text, std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (output().find(text) == std::string::npos) {
        if (Clock::now() >= deadline) return false;
        std::this_thread::sleep_for(poll_interval);
    }
    return true;
}

RunResult run_command(std::vector<std::string> argv, std::chrono::milliseconds timeout) {
    ChildProcess child(std::move(argv));
    const auto status = child.wait(timeout);
    RunResult result;
    if (!status) {
        child.signal(SIGKILL);
        child.wait(std::chrono::seconds(5));
        result.status = -1;
    } else {
        result.status = *status;
    }
    result.output = child.output();
    return result;
}

std::vector<std::string> needed_libraries(const std::string& binary) {
    const auto result = run_command({"/usr/bin/readelf", "-d", binary}, std::chrono::seconds(30));
    std::vector<std::string> names;
    const std::regex needed(R"(\(NEEDED\)\s+Shared library: \[([^\]]+)\])");
    for (std::sregex_iterator it(result.output.begin(), result.output.end(), needed), end;
         it != end; ++it) {
        names.push_back((*it)[1]);
    }
    return names;
}

}  // namespace eip2mqtt::test
