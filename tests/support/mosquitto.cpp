#include "tests/support/mosquitto.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <pwd.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/text_file.hpp"

namespace eip2mqtt::test {
namespace {

constexpr const char* kMosquitto = "/usr/sbin/mosquitto";
constexpr const char* kMosquittoPasswd = "/usr/bin/mosquitto_passwd";
constexpr auto kStartDeadline = std::chrono::seconds(10);
constexpr auto kPollInterval = std::chrono::milliseconds(10);
// How long a broker told to stop has before it is told again, and before it is killed.
constexpr auto kTermResendInterval = std::chrono::seconds(2);
constexpr auto kStopDeadline = std::chrono::seconds(30);

std::string current_user() {
    if (const passwd* pw = ::getpwuid(::geteuid())) {
        return pw->pw_name;
    }
    return "root";
}

/// A password file for `users` in `dir`, made by mosquitto_passwd.
void write_passwords(const std::vector<std::pair<std::string, std::string>>& users,
                     const std::string& dir) {
    for (std::size_t i = 0; i < users.size(); ++i) {
        std::vector<std::string> argv{kMosquittoPasswd, "-b"};
        if (i == 0) {
            argv.emplace_back("-c");
        }
        argv.insert(argv.end(), {dir + "/passwd", users[i].first, users[i].second});
        const auto result = run_command(std::move(argv), kStartDeadline);
        if (result.status != 0) {
            throw std::runtime_error("mosquitto_passwd failed: " + result.output);
        }
    }
}

/// The secure listener's lines: TLS, and passwords when there are users.
void write_secure_listener(std::ofstream& conf, const MosquittoOptions& options,
                           const std::string& dir, std::uint16_t secure_port) {
    conf << "listener " << secure_port << " 127.0.0.1\n";
    if (options.tls) {
        conf << "cafile " << options.tls->ca_file << "\n"
             << "certfile " << options.tls->cert_file << "\n"
             << "keyfile " << options.tls->key_file << "\n"
             << "require_certificate " << (options.tls->require_certificate ? "true" : "false")
             << "\n";
    }
    if (options.users.empty()) {
        conf << "allow_anonymous true\n";
    } else {
        conf << "allow_anonymous false\n"
             << "password_file " << dir << "/passwd\n";
    }
}

/// `dir`/mosquitto.conf: the plain listener on `port`, and the secure one on `secure_port`
/// (0: none).
void write_config(const MosquittoOptions& options, const std::string& dir, std::uint16_t port,
                  std::uint16_t secure_port) {
    std::ofstream conf(dir + "/mosquitto.conf");
    if (secure_port != 0) {
        // allow_anonymous and password_file then apply to the listener they follow.
        conf << "per_listener_settings true\n";
    }
    conf << "listener " << port << " 127.0.0.1\n"
         << "allow_anonymous true\n"
         // As root, Mosquitto would switch to the "mosquitto" user and lose access to dir.
         << "user " << current_user() << "\n"
         << "log_dest file " << dir << "/mosquitto.log\n"
         << "log_type all\n"
         << "connection_messages true\n";
    if (options.persistence) {
        conf << "persistence true\n"
             << "persistence_location " << dir << "/\n"
             << "persistence_file mosquitto.db\n";
    } else {
        conf << "persistence false\n";
    }
    if (secure_port != 0) write_secure_listener(conf, options, dir, secure_port);
    conf << options.extra_config << "\n";
}

}  // namespace

Mosquitto::Mosquitto(MosquittoOptions options) : options_(std::move(options)) {
    port_ = options_.port != 0 ? options_.port : free_tcp_port();
    std::string templ = (std::filesystem::temp_directory_path() / "eip2mqtt-mosquitto-XXXXXX");
    if (::mkdtemp(templ.data()) == nullptr) {
        throw std::runtime_error(std::string("mkdtemp: ") + std::strerror(errno));
    }
    dir_ = templ;
    if (options_.tls.has_value() || !options_.users.empty()) {
        do {
            secure_port_ = free_tcp_port();
        } while (secure_port_ == port_);
    }
    write_passwords(options_.users, dir_);
    write_config(options_, dir_, port_, secure_port_);

    try {
        start();
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
        throw;
    }
}

Mosquitto::~Mosquitto() {
    stop();
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
}

std::string Mosquitto::url() const { return "tcp://127.0.0.1:" + std::to_string(port_); }

std::string Mosquitto::secure_url() const {
    return (options_.tls ? "ssl://127.0.0.1:" : "tcp://127.0.0.1:") + std::to_string(secure_port_);
}

std::string Mosquitto::log() const { return read_text_file(dir_ + "/mosquitto.log"); }

void Mosquitto::start() {
    if (pid_ > 0) {
        return;
    }
    const std::string conf = dir_ + "/mosquitto.conf";
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) {
        throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    }
    if (pid == 0) {
        end_with_parent(parent);
        // Child: keep the test's output clean; the broker logs to its file.
        const int devnull = ::open("/dev/null", O_RDWR);
        if (devnull >= 0) {
            ::dup2(devnull, STDIN_FILENO);
            ::dup2(devnull, STDOUT_FILENO);
            ::dup2(devnull, STDERR_FILENO);
        }
        ::execl(kMosquitto, kMosquitto, "-c", conf.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    pid_ = pid;

    // Event polling with a bound: the broker gives no readiness signal but its listening port.
    const auto deadline = std::chrono::steady_clock::now() + kStartDeadline;
    while (!accepts_connections(port_) ||
           (secure_port_ != 0 && !accepts_connections(secure_port_))) {
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) {
            pid_ = -1;
            throw std::runtime_error("mosquitto exited at start-up; log:\n" +
                                     read_text_file(dir_ + "/mosquitto.log"));
        }
        if (std::chrono::steady_clock::now() > deadline) {
            stop();
            throw std::runtime_error("mosquitto did not accept connections within 10 s; log:\n" +
                                     read_text_file(dir_ + "/mosquitto.log"));
        }
        std::this_thread::sleep_for(kPollInterval);
    }
}

void Mosquitto::kill() {
    if (pid_ <= 0) {
        return;
    }
    ::kill(pid_, SIGKILL);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
}

void Mosquitto::stop() {
    if (pid_ <= 0) {
        return;
    }
    // Mosquitto sets its loop running after its listeners accept: a SIGTERM that falls between
    // the two is lost, and the broker runs on. So the signal is sent again until it ends, and
    // after a bound it is killed.
    const auto give_up = std::chrono::steady_clock::now() + kStopDeadline;
    auto resend = std::chrono::steady_clock::time_point{};
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
        const auto now = std::chrono::steady_clock::now();
        if (now > give_up) {
            ::kill(pid_, SIGKILL);
            while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
            }
            break;
        }
        if (now >= resend) {
            ::kill(pid_, SIGTERM);
            ::kill(pid_, SIGCONT);  // a test may have stopped it with SIGSTOP
            resend = now + kTermResendInterval;
        }
        std::this_thread::sleep_for(kPollInterval);
    }
    pid_ = -1;
}

}  // namespace eip2mqtt::test
