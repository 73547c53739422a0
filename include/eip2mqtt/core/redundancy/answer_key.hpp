#pragma once
/// What names a write's answer alike on both units of a pair (docs/redundancy.md,
/// "Writes"): both receive the same MQTT write, so its response topic and correlation data are
/// the same on both. The leader lists the keys of the writes it answered in its images, so a
/// standby taking over knows them answered even when it never heard the answers themselves.
/// Writes to one topic without correlation data share a key: their client cannot tell their
/// answers apart either.

#include <cstdint>
#include <string_view>

namespace eip2mqtt::core::redundancy {

/// 64-bit FNV-1a of the response topic, a NUL (which no topic holds) and the correlation data:
/// stable across builds and machines, as both units of a pair must compute it alike.
std::uint64_t answer_key(std::string_view response_topic, std::string_view correlation_data);

}  // namespace eip2mqtt::core::redundancy
