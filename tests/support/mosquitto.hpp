#pragma once
/// A real Mosquitto broker on a free loopback port, started and stopped by the test.

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::test {

/// TLS on the secure listener (PEM files, e.g. from TlsCerts).
struct MosquittoTls {
    std::string ca_file;
    std::string cert_file;
    std::string key_file;
    bool require_certificate = false;  ///< clients must present a certificate signed by ca_file
};

struct MosquittoOptions {
    std::uint16_t port = 0;    ///< 0: pick a free one
    bool persistence = false;  ///< keep sessions and retained messages across restarts
    std::string extra_config;  ///< appended to the generated mosquitto.conf

    /// With `tls` or `users`, a second, "secure" listener on secure_port(): TLS when `tls` is
    /// set, and password authentication (allow_anonymous false, a password file made with
    /// mosquitto_passwd) when `users` is not empty. The plain listener on port() stays open to
    /// anonymous clients, for the test's recorder.
    std::optional<MosquittoTls> tls;
    std::vector<std::pair<std::string, std::string>> users;  ///< (name, password)
};

class Mosquitto {
public:
    /// Starts the broker and returns once it accepts TCP connections (fails the test after 10 s).
    explicit Mosquitto(MosquittoOptions options = {});
    ~Mosquitto();
    Mosquitto(const Mosquitto&) = delete;
    Mosquitto& operator=(const Mosquitto&) = delete;

    std::uint16_t port() const { return port_; }
    std::string url() const;  ///< tcp://127.0.0.1:PORT
    /// The secure listener's port (0 without one) and URL: ssl://127.0.0.1:PORT with TLS,
    /// tcp://127.0.0.1:PORT with authentication only.
    std::uint16_t secure_port() const { return secure_port_; }
    std::string secure_url() const;

    /// Stops the broker (SIGTERM, then waits for it to exit).
    void stop();
    /// Kills the broker (SIGKILL, as a crash would: nothing saved since its last autosave) and
    /// waits for it to end.
    void kill();
    /// Starts it again on the same port, with the same persistence directory.
    void start();
    bool running() const { return pid_ > 0; }
    pid_t pid() const { return pid_; }
    /// Directory holding mosquitto.conf, the log and persistence.
    const std::string& dir() const { return dir_; }
    /// The broker's log so far.
    std::string log() const;

private:
    MosquittoOptions options_;
    std::uint16_t port_ = 0;
    std::uint16_t secure_port_ = 0;
    std::string dir_;
    pid_t pid_ = -1;
};

}  // namespace eip2mqtt::test
