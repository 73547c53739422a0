#include "tests/support/faulty_plc.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>

namespace eip2mqtt::test {

FaultyPlc::FaultyPlc(int fd, std::function<std::vector<std::byte>(std::uint64_t)> make,
                     std::vector<Destination> destinations, std::chrono::milliseconds period,
                     Clock::time_point epoch)
    : fd_(fd),
      make_(std::move(make)),
      destinations_(std::move(destinations)),
      period_(period),
      epoch_(epoch) {
    for (const auto& d : destinations_) models_.emplace_back(d.faults);
    thread_ = std::thread([this] { run(); });
}

FaultyPlc::~FaultyPlc() {
    stop();
    ::close(fd_);
}

void FaultyPlc::stop() {
    {
        const std::lock_guard lock(mutex_);
        stop_ = true;
    }
    cv_.notify_all();
    if (thread_.joinable()) thread_.join();
}

std::vector<FaultyPlc::Emission> FaultyPlc::log() const {
    const std::lock_guard lock(mutex_);
    return log_;
}

void FaultyPlc::run() {
    auto next = Clock::now();
    std::uint64_t n = 0;
    std::unique_lock lock(mutex_);
    while (!stop_) {
        auto wake = next;
        for (const auto& d : queue_) wake = std::min(wake, d.at);
        cv_.wait_until(lock, wake, [&] { return stop_; });
        if (stop_) break;
        const auto now = Clock::now();
        lock.unlock();
        if (now >= next) {
            produce(++n, now);
            next += period_;  // from the previous deadline: no drift
        }
        send_due(Clock::now());
        lock.lock();
    }
}

void FaultyPlc::produce(std::uint64_t n, Clock::time_point now) {
    const auto original = make_(n);
    for (std::size_t i = 0; i < models_.size(); ++i) {
        for (auto& emission : models_[i].on_datagram(original)) {
            const bool intact = emission.bytes == original;
            queue_.push_back({now + emission.delay, i, n, std::move(emission.bytes), intact});
        }
    }
}

void FaultyPlc::send_due(Clock::time_point now) {
    // Stable: of two due at once, the one queued first leaves first, as the model ordered them.
    std::stable_sort(queue_.begin(), queue_.end(),
                     [](const Due& a, const Due& b) { return a.at < b.at; });
    std::size_t sent = 0;
    for (; sent < queue_.size() && queue_[sent].at <= now; ++sent) {
        auto& due = queue_[sent];
        const auto& to = destinations_[due.destination];
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_port = htons(to.port);
        ::inet_pton(AF_INET, to.address.c_str(), &address.sin_addr);
        ::sendto(fd_, due.bytes.data(), due.bytes.size(), 0,
                 reinterpret_cast<const sockaddr*>(&address), sizeof address);
        const auto at =
            std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - epoch_);
        const std::lock_guard lock(mutex_);
        log_.push_back({due.destination, at, due.made_as, std::move(due.bytes), due.intact});
    }
    queue_.erase(queue_.begin(), queue_.begin() + static_cast<std::ptrdiff_t>(sent));
}

}  // namespace eip2mqtt::test
