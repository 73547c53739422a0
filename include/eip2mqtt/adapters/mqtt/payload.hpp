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

/// A produced exchange's `_status` (docs/mqtt-api.md "Exchange status").
struct ProducedStatus {
    bool paused = false;           ///< sends fail
    std::uint16_t request_id = 0;  ///< of the next datagram
    std::uint64_t sent = 0;
    std::uint64_t send_errors = 0;
    std::uint64_t skipped_deadlines = 0;
    std::uint64_t writes_applied = 0;
    std::uint64_t writes_pending = 0;
};

/// `{"state":"producing","request_id":…,"sent":…,"send_errors":…,"skipped_deadlines":…,
/// "writes_applied":…,"writes_pending":…}`; state "paused" while sends fail.
std::string format_produced_status_payload(const ProducedStatus& status);

/// A write's result (docs/mqtt-api.md "Results"): `{"ok":true}` without `error`, else
/// `{"error":…,"ok":false}` (keys in order). Bytes of `error` that are not UTF-8 become U+FFFD, so
/// that the result stays JSON whatever a client put in the names the message quotes.
std::string format_write_result(std::optional<std::string_view> error = std::nullopt);

/// Appends `text` as a JSON string, quoted and escaped: tag names may hold `"` and a backslash.
void append_json_string(std::string& out, std::string_view text);

/// Milliseconds since 1970 UTC of a header timestamp (seconds + nanoseconds).
std::int64_t timestamp_ms(std::uint32_t seconds, std::uint32_t nanoseconds);

}  // namespace eip2mqtt::adapters::mqtt
