#pragma once
/// A producer of datagrams for the integration tests: sends datagram `n` (1, 2, ...) every
/// `period` from a thread of its own. It can be paused, so that a test knows which datagrams the
/// gateway has been sent.

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
    /// Starts sending at once: `make(n)` through `send`, then a pause of `period`.
    PacedProducer(std::function<std::vector<std::byte>(std::uint64_t)> make,
                  std::function<void(const std::vector<std::byte>&)> send,
                  std::chrono::milliseconds period);
    ~PacedProducer();
    PacedProducer(const PacedProducer&) = delete;
    PacedProducer& operator=(const PacedProducer&) = delete;

    /// Stops sending; returns the number of the last datagram sent.
    std::uint64_t pause();
    void resume();
    /// The number of the last datagram sent.
    std::uint64_t last();

private:
    std::mutex mutex_;
    std::condition_variable cv_;
    bool paused_ = false;
    bool stop_ = false;
    std::uint64_t last_ = 0;
    std::thread thread_;
};

}  // namespace eip2mqtt::test
