#pragma once
/// The payloads of the JSON topic tree (docs/mqtt-api.md), every one of them built here. The
/// data path's small, fixed-shape objects (tag values, `_values`, `_status`) are written with
/// fmt, without a JSON document in between; those that quote what a client sent (write results)
/// or change shape with the code (metrics) go through nlohmann.

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/json_text.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/quality/quality.hpp"

namespace eip2mqtt::app::northbound::json_tree {

/// The data message of the raw sample `raw` of `tag` of exchange `exchange`, in the profile
/// `format`: json `{"value":90,"timestamp":1695231678000,"quality":"good"}` (followed by
/// `"limit":"low"|"high"` when the raw value left its range and by `"raw":…` with publish_raw),
/// raw `90`, value `90` (a string bare), umh `{"value":90,"timestamp_ms":…}`, kepware
/// `{"timestamp":…,"values":[{"id":"exchange.tag","v":90,"q":true,"t":…}]}`. A scaled tag's value
/// is its engineering value.
void format_tag_payload(std::string& out, std::string_view exchange, const core::plan::TagSpec& tag,
                        const core::plan::Value& raw, core::quality::Quality quality,
                        std::int64_t timestamp_ms, core::config::PayloadFormat format);

/// Batch mode's `_values`: `{"timestamp":…,"quality":"good","values":{"A":1,"B":2.5}}` with the
/// batch's samples as published (engineering values), in `out` (cleared first); with kepware,
/// `{"timestamp":…,"values":[{"id":"exchange.A","v":1,"q":true,"t":…},…]}`.
void format_values_payload(std::string& out, const SampleBatch& batch,
                           core::config::PayloadFormat format = core::config::PayloadFormat::json);

/// Adds to `message` the MQTT 5 user properties `chosen` (mqtt.properties) of a data message:
/// of tag `tag` of `plan`, or of the exchange's `_values` (`tag` null, no `unit`): `unit` (when
/// the tag has one), `quality`, `source_time` (milliseconds since 1970, as the payloads'),
/// `exchange` (its name) and `producer` (its producer id).
void add_data_properties(adapters::mqtt::Message& message,
                         std::span<const core::config::MessageProperty> chosen,
                         const core::plan::ExchangePlan& plan, const core::plan::TagSpec* tag,
                         core::quality::Quality quality, std::int64_t timestamp_ms);

/// `{"state":"ok","request_id":…,"received":…,"missed":…,"duplicates":…,"out_of_order":…,
/// "last_seen":…,"clock":"synced","clock_offset_ms":…}` plus the mismatch, timeout and restart
/// counters. last_seen is the wall time of the last accepted datagram in ms, null before the
/// first; clock_offset_ms the producer's time minus the receive time of the last stamped
/// datagram, null before one.
std::string format_status_payload(const ConsumedStatus& status);

/// `{"state":"producing","request_id":…,"sent":…,"send_errors":…,"skipped_deadlines":…,
/// "writes_applied":…,"writes_pending":…,"saved":true,"save_failures":…,"save_error":null}`;
/// state "paused" while sends fail, save_error the text of the last failed save until one
/// succeeds.
std::string format_produced_status_payload(const ProducedStatus& status);

/// A write's result (docs/mqtt-api.md "Results"): `{"ok":true}` without `error`, else
/// `{"error":…,"ok":false}` (keys in order). Bytes of `error` that are not UTF-8 become U+FFFD, so
/// that the result stays JSON whatever a client put in the names the message quotes.
std::string format_write_result(std::optional<std::string_view> error = std::nullopt);

/// The result of a write applied and sent, whose image could not be saved:
/// `{"error":"not saved: …","ok":true,"saved":false}` (keys in order; UTF-8 as above).
std::string format_write_result_unsaved(std::string_view reason);

/// The payload of `_gateway/{id}/metrics` (docs/schema/metrics.json).
std::string metrics_json(const MetricsSources& sources, std::chrono::seconds uptime);

/// Appends `text` as a JSON string, quoted and escaped: tag names may hold `"` and a backslash.
using core::append_json_string;

}  // namespace eip2mqtt::app::northbound::json_tree
