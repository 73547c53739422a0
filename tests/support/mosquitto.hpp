#pragma once
/// A real Mosquitto broker on a free loopback port, started and stopped by the test.

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <string>

namespace eip2mqtt::test {

struct MosquittoOptions {
    std::uint16_t port = 0;    ///< 0: pick a free one
    bool persistence = false;  ///< keep sessions and retained messages across restarts
    std::string extra_config;  ///< appended to the generated mosquitto.conf
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

    /// Stops the broker (SIGTERM, then waits for it to exit).
    void stop();
    /// Starts it again on the same port, with the same persistence directory.
    void start();
    bool running() const { return pid_ > 0; }
    /// Directory holding mosquitto.conf, the log and persistence.
    const std::string& dir() const { return dir_; }

private:
    MosquittoOptions options_;
    std::uint16_t port_ = 0;
    std::string dir_;
    pid_t pid_ = -1;
};

}  // namespace eip2mqtt::test
