#pragma once
// A fake Producible (what the ProducerScheduler knows of a produced exchange): each call is
// written to a log the test reads.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/app/exchanges/producer_scheduler.hpp"

namespace eip2mqtt::test {

/// A Producible that records each call, in one log shared by every producer of a test.
class RecordingProducible final : public app::Producible {
public:
    RecordingProducible(std::string name, std::uint16_t port, std::vector<std::string>& log)
        : name_(std::move(name)), destination_{0x7F000001, port}, log_(log) {}

    std::span<const std::byte> produce(core::WallTime wall) override {
        log_.push_back("produce " + name_);
        stamps_.push_back(wall);
        datagram_.assign(4, std::byte{static_cast<unsigned char>(destination_.port)});
        return datagram_;
    }
    const adapters::udp::Endpoint& destination() const override { return destination_; }
    void count_skipped(std::size_t skipped) override { skipped_ += skipped; }
    void on_sent(bool sent, core::WallTime) override {
        log_.push_back((sent ? "sent " : "refused ") + name_);
    }

    std::size_t skipped_ = 0;
    std::vector<core::WallTime> stamps_;  ///< the wall time each datagram was produced for

private:
    std::string name_;
    adapters::udp::Endpoint destination_;
    std::vector<std::string>& log_;
    std::vector<std::byte> datagram_;
};

}  // namespace eip2mqtt::test
