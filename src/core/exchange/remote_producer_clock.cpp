#include "eip2mqtt/core/exchange/remote_producer_clock.hpp"

namespace eip2mqtt::core::exchange {

RemoteProducerClock::RemoteProducerClock(plan::TimestampSource source,
                                         std::chrono::milliseconds tolerance)
    : source_(source), tolerance_(tolerance) {}

std::int64_t RemoteProducerClock::on_datagram(std::uint32_t time_s, std::uint32_t time_ns,
                                              std::int64_t receive_ms) {
    if (time_s == 0) {
        state_ = ClockState::none;
        return receive_ms;
    }
    const std::int64_t producer_ms = std::int64_t{time_s} * 1000 + time_ns / 1000000;
    const std::int64_t offset = producer_ms - receive_ms;
    offset_ms_ = offset;
    const bool synced = (offset < 0 ? -offset : offset) <= tolerance_.count();
    state_ = synced ? ClockState::synced : ClockState::unsynced;
    switch (source_) {
        case plan::TimestampSource::receive:
            return receive_ms;
        case plan::TimestampSource::producer:
            return producer_ms;
        case plan::TimestampSource::automatic:
            break;
    }
    return synced ? producer_ms : receive_ms;
}

}  // namespace eip2mqtt::core::exchange
