#pragma once
/// The samples of one journal entry as bytes: for each tag, its index in the
/// exchange and its value, compactly, since an outage of hours journals millions of them. The
/// index means something only with the exchange's layout, which the journal keeps beside it.
///
/// Per sample: the tag index (LEB128), one kind byte (bool false/true, int64, uint64, float,
/// double, text, array), then the value: nothing for a bool, zigzag LEB128 for an int64, LEB128
/// for a uint64, 4 or 8 little-endian bytes for a float or a double, LEB128 size and UTF-8 for
/// a text, LEB128 count and each element's kind and value for an array.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::adapters::history {

struct JournaledSample {
    std::uint32_t tag = 0;
    core::plan::Value value;
};

/// Appends the encoding of `samples` to `out`.
void encode_samples(std::span<const JournaledSample> samples, std::string& out);

/// The samples of `bytes`; an error text for bytes that are not an encoding of ours.
core::Result<std::vector<JournaledSample>, std::string> decode_samples(std::string_view bytes);

}  // namespace eip2mqtt::adapters::history
