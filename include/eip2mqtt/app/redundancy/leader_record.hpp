#pragma once
/// The leader topic's payload (docs/schema/leader.json): the pair's leader record as JSON, with
/// the leader's watermarks.

#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "eip2mqtt/core/redundancy/lease.hpp"
#include "eip2mqtt/core/redundancy/sample_key.hpp"

namespace eip2mqtt::app::redundancy {

/// Of each consumed exchange, by its topic under the base, the newest sample whose publication
/// the broker acknowledged to the leader (core/redundancy/acked_watermarks.hpp).
using Watermarks = std::map<std::string, core::redundancy::SampleKey, std::less<>>;

/// `{"id":"gw-a","epoch":3,"priority":100,"takeover_ms":2000}`, with `"claim":true` on a claim,
/// `"bd_seq":n` on a renewal of a leader whose Sparkplug session is open, and with watermarks
/// `"watermarks":{"line/1":[4711,1695231678,123456789]}`: each sample's request id, the
/// seconds and nanoseconds of its producer's timestamp, and its change of quality when not 0.
/// Each record carries `"beat":n` (LeaderRecord::beat) and a claim what it heard:
/// `"heard":{"id":"gw-b","epoch":2,"beat":n}`.
std::string encode_leader_record(const core::redundancy::LeaderRecord& record,
                                 std::chrono::milliseconds takeover,
                                 const Watermarks& watermarks = {});

/// The record of a payload; nullopt for an empty one (cleared by a will) or one that does not
/// read as a record (it is not a leader: the time since the last one runs on). `watermarks`,
/// when given, gets those of the record (none when it has none); one that does not read as a
/// sample is left out.
std::optional<core::redundancy::LeaderRecord> decode_leader_record(
    std::string_view payload, Watermarks* watermarks = nullptr);

}  // namespace eip2mqtt::app::redundancy
