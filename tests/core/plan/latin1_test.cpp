// String tags' Latin-1 bytes and the UTF-8 text MQTT carries, both ways.

#include "eip2mqtt/core/plan/latin1.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

std::vector<std::byte> bytes(const std::string& s) {
    std::vector<std::byte> out;
    for (const char c : s) out.push_back(static_cast<std::byte>(c));
    return out;
}

TEST(Latin1, EveryByteIsTheCodePointOfItsNumber) {
    EXPECT_EQ(latin1_to_utf8(bytes("Batch 7"), false), "Batch 7");
    EXPECT_EQ(latin1_to_utf8(bytes("\xB0"
                                   "C"),
                             false),
              "\xC2\xB0"
              "C");  // degree sign
    EXPECT_EQ(latin1_to_utf8(bytes("\xE9t\xE9"), false), "\xC3\xA9t\xC3\xA9");
    EXPECT_EQ(latin1_to_utf8(bytes("\xFF"), false), "\xC3\xBF");
    EXPECT_EQ(latin1_to_utf8(bytes("\x80"), false), "\xC2\x80");
}

TEST(Latin1, TrimRemovesOnlyTrailingNulsAndSpaces) {
    EXPECT_EQ(latin1_to_utf8(bytes(std::string("AB \0 \0\0", 7)), true), "AB");
    EXPECT_EQ(latin1_to_utf8(bytes(std::string(" A\0B", 4)), true), std::string(" A\0B", 4));
    EXPECT_EQ(latin1_to_utf8(bytes(std::string("\0\0", 2)), true), "");
    EXPECT_EQ(latin1_to_utf8(bytes(std::string("AB \0", 4)), false), std::string("AB \0", 4));
}

TEST(Latin1, TextWithALatin1FormIsEncoded) {
    EXPECT_EQ(utf8_to_latin1("Batch 7"), "Batch 7");
    EXPECT_EQ(utf8_to_latin1("\xC2\xB0"
                             "C"),
              "\xB0"
              "C");
    EXPECT_EQ(utf8_to_latin1("\xC3\xBF"), "\xFF");
    EXPECT_EQ(utf8_to_latin1(""), "");
}

TEST(Latin1, TextBeyondLatin1OrNoUtf8IsRefused) {
    EXPECT_EQ(utf8_to_latin1("\xE2\x82\xAC"), std::nullopt);      // euro sign, U+20AC
    EXPECT_EQ(utf8_to_latin1("\xC5\x81"), std::nullopt);          // U+0141
    EXPECT_EQ(utf8_to_latin1("\xF0\x9F\x98\x80"), std::nullopt);  // an emoji
    EXPECT_EQ(utf8_to_latin1("\xC3"), std::nullopt);              // cut short
    EXPECT_EQ(utf8_to_latin1("\xC3"
                             "A"),
              std::nullopt);                              // no continuation byte
    EXPECT_EQ(utf8_to_latin1("\xC1\xBF"), std::nullopt);  // overlong "?"
    EXPECT_EQ(utf8_to_latin1("\xFF"), std::nullopt);
}

TEST(Latin1, EveryByteRoundTrips) {
    for (int b = 0; b < 256; ++b) {
        const std::string one(1, static_cast<char>(b));
        EXPECT_EQ(utf8_to_latin1(latin1_to_utf8(bytes(one), false)), one) << b;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
