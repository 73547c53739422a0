#pragma once
/// Tags that share bits of an exchange's data. Point lists name a status word and each of its
/// bits, or a dint and its two halves, at the same bytes: valid, but a single write must not set
/// two of them (which would win?), and `check` shows them.

#include <cstddef>
#include <span>
#include <vector>

#include "eip2mqtt/core/plan/tag_plan.hpp"

namespace eip2mqtt::core::plan {

/// The bits a tag occupies in the data: [first, first + count), bit 8*b+k being bit k of byte b.
struct BitSpan {
    std::size_t first = 0;
    std::size_t count = 0;

    friend bool operator==(const BitSpan&, const BitSpan&) = default;
};

BitSpan bit_span(const TagSpec& tag);

/// Two positions in the list given to find_overlaps, the one that starts first (or, starting
/// together, comes first in the list) as `first`.
struct OverlapPair {
    std::size_t first = 0;
    std::size_t second = 0;

    friend bool operator==(const OverlapPair&, const OverlapPair&) = default;
};

struct Overlaps {
    std::vector<OverlapPair> listed;  ///< at most `limit`, by where they start
    std::size_t total = 0;            ///< every overlapping pair, counted without listing
};

/// Finds the pairs of spans (none empty) that share a bit in O(n log n + limit): 10,000 tags on
/// one word make 50 million pairs, which are counted, not listed.
Overlaps find_overlaps(std::span<const BitSpan> spans, std::size_t limit);

}  // namespace eip2mqtt::core::plan
