// Which tags share bits (docs/protocol.md "Point lists"): a word and its bits, a dint
// and its halves, and the bounded listing `check` relies on.

#include "eip2mqtt/core/plan/overlap.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

TagSpec tag(std::uint16_t byte, std::uint8_t bit, TagType type) {
    TagSpec spec;
    spec.address = {byte, bit};
    spec.type = type;
    return spec;
}

std::vector<BitSpan> spans(const std::vector<TagSpec>& tags) {
    std::vector<BitSpan> out;
    for (const auto& t : tags) out.push_back(bit_span(t));
    return out;
}

TEST(BitSpan, CoversTheTagsBits) {
    EXPECT_EQ(bit_span(tag(2, 0, TagType::int_)), (BitSpan{16, 16}));
    EXPECT_EQ(bit_span(tag(2, 5, TagType::bit)), (BitSpan{21, 1}));
    EXPECT_EQ(bit_span(tag(0, 0, TagType::lreal)), (BitSpan{0, 64}));
}

TEST(FindOverlaps, AWordAndItsBits) {
    const auto s = spans({tag(0, 3, TagType::bit), tag(0, 0, TagType::word),
                          tag(1, 7, TagType::bit), tag(2, 0, TagType::bit)});
    const auto found = find_overlaps(s, 10);
    EXPECT_EQ(found.total, 2u);
    EXPECT_EQ(found.listed, (std::vector<OverlapPair>{{1, 0}, {1, 2}}));
}

TEST(FindOverlaps, ADintAndItsHalves) {
    const auto s = spans({tag(0, 0, TagType::dint), tag(0, 0, TagType::int_),
                          tag(2, 0, TagType::int_), tag(4, 0, TagType::dint)});
    const auto found = find_overlaps(s, 10);
    EXPECT_EQ(found.listed, (std::vector<OverlapPair>{{0, 1}, {0, 2}}));
    EXPECT_EQ(found.total, 2u);
}

TEST(FindOverlaps, NeighboursAndDifferentBitsOfOneByteDoNotOverlap) {
    const auto s = spans({tag(0, 0, TagType::int_), tag(2, 0, TagType::int_),
                          tag(4, 0, TagType::bit), tag(4, 1, TagType::bit)});
    EXPECT_EQ(find_overlaps(s, 10).total, 0u);
    // The same bit twice does.
    const auto same = spans({tag(4, 1, TagType::bit), tag(4, 1, TagType::bit)});
    EXPECT_EQ(find_overlaps(same, 10).listed, (std::vector<OverlapPair>{{0, 1}}));
}

TEST(FindOverlaps, ListsAtMostTheLimitButCountsEveryPair) {
    std::vector<TagSpec> tags(2000, tag(0, 0, TagType::int_));
    const auto found = find_overlaps(spans(tags), 5);
    EXPECT_EQ(found.listed.size(), 5u);
    EXPECT_EQ(found.total, 2000u * 1999u / 2u);
    EXPECT_EQ(find_overlaps(spans(tags), 0).listed.size(), 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
