#pragma once
// A thread sending datagram `n` (1, 2, ...) every `period`, pausable so that a test knows what
// it sent: the steady traffic of the outage tests.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace eip2mqtt::test {

class PacedProducer {
public:
    PacedProducer(std::function<std::vector<std::byte>(std::uint64_t)> make,
                  std::function<void(const std::vector<std::byte>&)> send,
                  std::chrono::milliseconds period);
    ~PacedProducer();
    PacedProducer(const PacedProducer&) = delete;
    PacedProducer& operator=(const PacedProducer&) = delete;

    /// Stops sending; returns the last `n` sent.
    std::uint64_t pause();
    void resume();

private:
    std::mutex mutex_;
    std::condition_variable cv_;
    bool paused_ = false;
    bool stop_ = false;
    std::uint64_t last_ = 0;
    std::thread thread_;
};

}  // namespace eip2mqtt::test
