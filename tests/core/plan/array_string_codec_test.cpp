// Arrays and strings in an exchange's bytes: consecutive elements (bits at consecutive bits),
// strings as fixed Latin-1 fields, and what each tag occupies.

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/value_codec.hpp"

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

TagSpec tag(TagType type, std::uint16_t byte, std::uint8_t bit, std::uint16_t count) {
    TagSpec spec;
    spec.name = "T";
    spec.type = type;
    spec.address = {byte, bit};
    spec.count = count;
    return spec;
}

std::vector<Value> items(const Value& value) {
    const auto* list = list_items(value);
    return list != nullptr ? *list : std::vector<Value>{};
}

TEST(ArrayCodec, ElementsFollowEachOtherLittleEndian) {
    std::vector<std::byte> data(12);
    const auto t = tag(TagType::int_, 2, 0, 3);
    EXPECT_EQ(tag_size(t), 6u);
    encode_tag(
        data, t,
        make_list({Value{std::int64_t{1}}, Value{std::int64_t{-2}}, Value{std::int64_t{300}}}));
    EXPECT_EQ(data[2], std::byte{0x01});
    EXPECT_EQ(data[4], std::byte{0xFE});
    EXPECT_EQ(data[5], std::byte{0xFF});
    EXPECT_EQ(data[6], std::byte{0x2C});
    EXPECT_EQ(data[7], std::byte{0x01});
    EXPECT_EQ(items(decode_tag(data, t)),
              (std::vector<Value>{Value{std::int64_t{1}}, Value{std::int64_t{-2}},
                                  Value{std::int64_t{300}}}));
    EXPECT_EQ(element_address(t, 2), (Address{6, 0}));
}

TEST(ArrayCodec, BitsRunOnIntoTheNextByte) {
    std::vector<std::byte> data(3);
    const auto t = tag(TagType::bit, 0, 6, 4);  // 0.6, 0.7, 1.0, 1.1
    EXPECT_EQ(tag_size(t), 2u);
    EXPECT_EQ(element_address(t, 2), (Address{1, 0}));
    encode_tag(data, t, make_list({Value{true}, Value{false}, Value{true}, Value{true}}));
    EXPECT_EQ(data[0], std::byte{0x40});
    EXPECT_EQ(data[1], std::byte{0x03});
    EXPECT_EQ(items(decode_tag(data, t)),
              (std::vector<Value>{Value{true}, Value{false}, Value{true}, Value{true}}));
}

TEST(ArrayCodec, RealsKeepTheirPrecision) {
    std::vector<std::byte> data(8);
    const auto t = tag(TagType::real, 0, 0, 2);
    encode_tag(data, t, make_list({Value{1.1f}, Value{-71.5f}}));
    EXPECT_EQ(to_json(decode_tag(data, t)), "[1.1,-71.5]");
}

TEST(StringCodec, AFieldIsLatin1PaddedWithNuls) {
    std::vector<std::byte> data(8, std::byte{0x55});
    auto t = tag(TagType::string, 1, 0, 6);
    EXPECT_EQ(tag_size(t), 6u);
    encode_tag(data, t, make_text("\xC3\xA9t\xC3\xA9"));  // "été", 3 Latin-1 bytes
    EXPECT_EQ(data[0], std::byte{0x55});
    EXPECT_EQ(data[1], std::byte{0xE9});
    EXPECT_EQ(data[2], std::byte{'t'});
    EXPECT_EQ(data[3], std::byte{0xE9});
    EXPECT_EQ(data[4], std::byte{0});
    EXPECT_EQ(data[6], std::byte{0});
    EXPECT_EQ(data[7], std::byte{0x55});
    EXPECT_EQ(to_json(decode_tag(data, t)), "\"\xC3\xA9t\xC3\xA9\"");
}

TEST(StringCodec, PaddingIsTrimmedUnlessTheTagKeepsIt) {
    const std::string field("AB  \0\0", 6);
    std::vector<std::byte> data;
    for (const char c : field) data.push_back(static_cast<std::byte>(c));
    auto t = tag(TagType::string, 0, 0, 6);
    EXPECT_EQ(to_json(decode_tag(data, t)), "\"AB\"");
    EXPECT_EQ(to_json(decode_tag(data, t, Padding::keep)), "\"AB  \\u0000\\u0000\"");
    t.mutable_extras().trim = false;
    EXPECT_EQ(to_json(decode_tag(data, t)), "\"AB  \\u0000\\u0000\"");
}

TEST(StringCodec, AFieldWrittenBackAsReadKeepsItsBytes) {
    const std::string field("A \0B", 4);
    std::vector<std::byte> data;
    for (const char c : field) data.push_back(static_cast<std::byte>(c));
    const auto t = tag(TagType::string, 0, 0, 4);
    std::vector<std::byte> copy(4, std::byte{0x77});
    encode_tag(copy, t, decode_tag(data, t, Padding::keep));
    EXPECT_EQ(copy, data);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
