#pragma once
/// Payloads of the gateway's topics (docs/mqtt-api.md), written without a JSON library on the
/// hot path: they are small, fixed-shape objects.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/exchange/consumed_exchange.hpp"
#include "eip2mqtt/core/exchange/producer_clock.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/quality/quality.hpp"

namespace eip2mqtt::adapters::mqtt {

/// `{"value":90,"timestamp":1695231678000,"quality":"good"}`, or `90` with payload: raw.
void format_tag_payload(std::string& out, const core::plan::Value& value,
                        core::quality::Quality quality, std::int64_t timestamp_ms,
                        core::config::PayloadFormat format);

/// `{"state":"ok","request_id":…,"received":…,"missed":…,"duplicates":…,"out_of_order":…,
/// "last_seen":…,"clock":"synced","clock_offset_ms":…}` plus the mismatch, timeout and restart
/// counters. last_seen is the wall time of the last accepted datagram in ms, null before the
/// first; clock_offset_ms the producer's time minus the receive time of the last stamped
/// datagram, null before one.
std::string format_status_payload(const core::exchange::ConsumedExchange& exchange,
                                  std::optional<std::int64_t> last_seen_ms,
                                  const core::exchange::ProducerClock& clock);

/// Appends `text` as a JSON string, quoted and escaped: tag names may hold `"` and a backslash.
void append_json_string(std::string& out, std::string_view text);

/// Milliseconds since 1970 UTC of a header timestamp (seconds + nanoseconds).
std::int64_t timestamp_ms(std::uint32_t seconds, std::uint32_t nanoseconds);

}  // namespace eip2mqtt::adapters::mqtt
