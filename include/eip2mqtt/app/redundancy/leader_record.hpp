#pragma once
/// The leader topic's payload (docs/schema/leader.json): the pair's leader record as JSON.

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "eip2mqtt/core/redundancy/lease.hpp"

namespace eip2mqtt::app::redundancy {

/// `{"id":"gw-a","epoch":3,"priority":100,"takeover_ms":2000}`, with `"claim":true` on a claim
/// and `"bd_seq":n` on a renewal of a leader whose Sparkplug session is open.
std::string encode_leader_record(const core::redundancy::LeaderRecord& record,
                                 std::chrono::milliseconds takeover);

/// The record of a payload; nullopt for an empty one (cleared by a will) or one that does not
/// read as a record (it is not a leader: the time since the last one runs on).
std::optional<core::redundancy::LeaderRecord> decode_leader_record(std::string_view payload);

}  // namespace eip2mqtt::app::redundancy
