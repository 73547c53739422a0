#include "eip2mqtt/core/plan/overlap.hpp"

#include <algorithm>
#include <numeric>

#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"

namespace eip2mqtt::core::plan {

BitSpan bit_span(const TagSpec& tag) {
    const std::size_t byte_bit = std::size_t{tag.address.byte} * 8;
    if (tag.type == TagType::bit) return {byte_bit + (tag.address.bit & 7u), tag.count};
    return {byte_bit, tag_size(tag) * 8};
}

Overlaps find_overlaps(std::span<const BitSpan> spans, std::size_t limit) {
    std::vector<std::size_t> order(spans.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    // Stable: spans starting together keep their order in the list.
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return spans[a].first < spans[b].first; });

    // A span overlaps exactly the spans after it in this order that start before it ends:
    // each pair is found once, from the span that starts first, and counted by a binary search.
    Overlaps found;
    for (auto it = order.begin(); it != order.end(); ++it) {
        const auto end = spans[*it].first + spans[*it].count;
        const auto after = std::partition_point(
            it + 1, order.end(), [&](std::size_t i) { return spans[i].first < end; });
        found.total += static_cast<std::size_t>(after - (it + 1));
        for (auto other = it + 1; other != after && found.listed.size() < limit; ++other) {
            found.listed.push_back({*it, *other});
        }
    }
    return found;
}

}  // namespace eip2mqtt::core::plan
