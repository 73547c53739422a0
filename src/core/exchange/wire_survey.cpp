#include "eip2mqtt/core/exchange/wire_survey.hpp"

#include <algorithm>

namespace eip2mqtt::core::exchange {

Destination classify_destination(std::uint32_t address,
                                 std::span<const std::uint32_t> broadcast_addresses) {
    if (address == 0) return {};
    if ((address >> 28) == 0xE) return {DestinationKind::multicast, address};
    if (address == 0xFFFFFFFF || std::find(broadcast_addresses.begin(), broadcast_addresses.end(),
                                           address) != broadcast_addresses.end()) {
        return {DestinationKind::broadcast, address};
    }
    return {DestinationKind::unicast, address};
}

WireSurvey::WireSurvey(wire::ExchangeKey key, std::chrono::milliseconds clock_tolerance)
    // The clock's state is all that is read: which time the tags would carry does not matter.
    : clock_(plan::TimestampSource::automatic, clock_tolerance) {
    summary_.key = key;
    summary_.clock_tolerance = clock_tolerance;
}

void WireSurvey::on_datagram(const wire::Header& header, std::size_t data_length,
                             const Destination& destination, MonoTime now,
                             std::int64_t receive_ms) {
    auto& s = summary_;
    const auto length = static_cast<std::uint16_t>(std::min<std::size_t>(data_length, 0xFFFF));
    const auto signature = wire::Signature::from_wire(header.signature);
    const auto clock_before = clock_.state();
    clock_.on_datagram(header.time_s, header.time_ns, receive_ms);
    if (s.datagrams == 0) {
        s.min_length = s.max_length = length;
    } else {
        s.min_length = std::min(s.min_length, length);
        s.max_length = std::max(s.max_length, length);
        s.signature_varied = s.signature_varied || signature != s.signature;
        s.destination_varied = s.destination_varied || destination != s.destination;
        s.clock_varied = s.clock_varied || clock_.state() != clock_before;
    }
    ++s.datagrams;
    s.length = length;
    s.signature = signature;
    s.destination = destination;
    s.clock = clock_.state();
    s.clock_offset_ms = clock_.offset_ms();

    // The period: only datagrams that are new samples by their request id count.
    const auto rid = header.request_id;
    const auto forward = [&](const Sample& from) {
        const auto step = static_cast<std::uint16_t>(rid - from.rid);
        return step != 0 && step < 32768 ? step : 0;
    };
    if (!last_) {
        last_ = Sample{rid, now};
        return;
    }
    if (const auto step = forward(*last_); step != 0) {
        measure(*last_, step, now);
        behind_.reset();
    } else if (static_cast<std::uint16_t>(rid - last_->rid) != 0) {
        // Behind the last sample: late, or the first of a restarted producer. A second one in
        // sequence after it tells a restart: measure on from there.
        if (behind_ && forward(*behind_) != 0) {
            measure(*behind_, forward(*behind_), now);
            behind_.reset();
        } else {
            behind_ = Sample{rid, now};
        }
    }
}

void WireSurvey::measure(const Sample& from, std::uint16_t step, MonoTime now) {
    measured_ += now >= from.time ? now - from.time : std::chrono::nanoseconds(0);
    summary_.period_steps += step;
    summary_.period_ms = std::chrono::duration<double, std::milli>(measured_).count() /
                         static_cast<double>(summary_.period_steps);
    last_ = Sample{static_cast<std::uint16_t>(from.rid + step), now};
}

}  // namespace eip2mqtt::core::exchange
