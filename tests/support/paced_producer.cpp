#include "tests/support/paced_producer.hpp"

namespace eip2mqtt::test {

PacedProducer::PacedProducer(std::function<std::vector<std::byte>(std::uint64_t)> make,
                             std::function<void(const std::vector<std::byte>&)> send,
                             std::chrono::milliseconds period)
    : thread_([this, make = std::move(make), send = std::move(send), period] {
          std::unique_lock lock(mutex_);
          while (!stop_) {
              if (paused_) {
                  cv_.wait(lock, [this] { return stop_ || !paused_; });
                  continue;
              }
              const auto n = ++last_;
              lock.unlock();
              send(make(n));
              std::this_thread::sleep_for(period);  // pacing the traffic, not synchronising
              lock.lock();
          }
      }) {}

PacedProducer::~PacedProducer() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
}

std::uint64_t PacedProducer::pause() {
    std::lock_guard lock(mutex_);
    paused_ = true;
    return last_;
}

void PacedProducer::resume() {
    {
        std::lock_guard lock(mutex_);
        paused_ = false;
    }
    cv_.notify_all();
}

}  // namespace eip2mqtt::test
