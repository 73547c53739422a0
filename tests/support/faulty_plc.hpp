#pragma once
/// A PLC in user space that fails as a network would (this machine's kernel has no netem): it
/// sends datagram `n` of a consumed exchange every period to each of its destinations, through
/// the fault injector's model (tools/fault_injector/fault_model.hpp), seeded per destination:
/// lost, duplicated, held back behind the next one, delayed, corrupted. It logs each datagram
/// it sent, as it sent it, so that a test knows exactly what was on the wire. A thread of its
/// own, from the constructor to stop() or the destructor.

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "tools/fault_injector/fault_model.hpp"

namespace eip2mqtt::test {

class FaultyPlc {
public:
    using Clock = std::chrono::steady_clock;
    struct Destination {
        std::string address;  ///< dotted IPv4
        std::uint16_t port = 0;
        fault_injector::FaultConfig faults;
    };
    /// One datagram sent: to which destination (its index), when (since `epoch`), which
    /// datagram of the run it was made as, and its bytes as they left.
    struct Emission {
        std::size_t destination = 0;
        std::chrono::milliseconds at{0};
        std::uint64_t made_as = 0;
        std::vector<std::byte> bytes;
        bool intact = false;  ///< the bytes are those of datagram `made_as`, unchanged
    };

    /// Sends from `fd` (a UDP socket, bound where the PLC is; taken, closed at the end) the
    /// datagrams `make` makes, 1, 2, ..., every `period`.
    FaultyPlc(int fd, std::function<std::vector<std::byte>(std::uint64_t)> make,
              std::vector<Destination> destinations, std::chrono::milliseconds period,
              Clock::time_point epoch);
    ~FaultyPlc();
    FaultyPlc(const FaultyPlc&) = delete;
    FaultyPlc& operator=(const FaultyPlc&) = delete;

    /// Stops sending (what the models still held is dropped); returns once the thread ended.
    void stop();
    std::vector<Emission> log() const;

private:
    struct Due {
        Clock::time_point at;
        std::size_t destination;
        std::uint64_t made_as;
        std::vector<std::byte> bytes;
        bool intact;
    };
    void run();
    /// Hands datagram `n` to each destination's model, queueing what it emits.
    void produce(std::uint64_t n, Clock::time_point now);
    /// Sends every queued datagram that is due, oldest due first.
    void send_due(Clock::time_point now);

    int fd_;
    std::function<std::vector<std::byte>(std::uint64_t)> make_;
    std::vector<Destination> destinations_;
    std::vector<fault_injector::FaultModel> models_;
    std::chrono::milliseconds period_;
    Clock::time_point epoch_;
    std::vector<Due> queue_;  ///< the thread's only
    mutable std::mutex mutex_;
    std::condition_variable cv_;
    bool stop_ = false;
    std::vector<Emission> log_;
    std::thread thread_;
};

}  // namespace eip2mqtt::test
