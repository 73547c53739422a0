#include "eip2mqtt/core/plan/value_codec.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

using test::from_hex;
using test::to_hex;
namespace vectors = test::vectors;

std::vector<std::byte> data_of(std::string_view hex) {
    const auto bytes = from_hex(hex);
    return {bytes.begin() + wire::header_size, bytes.end()};
}

Address at(std::uint16_t byte, std::uint8_t bit = 0) { return {byte, bit}; }

TEST(Vectors, V1DecodesEveryTag) {
    const auto data = data_of(vectors::v1);
    const bool bits[8] = {true, true, true, false, false, true, true, true};
    for (std::uint8_t b = 0; b < 8; ++b) {
        EXPECT_EQ(decode_value(data, TagType::bit, at(0, b)), Value{bits[b]}) << "bit 0." << +b;
    }
    EXPECT_EQ(decode_value(data, TagType::word, at(1)), Value{std::uint64_t{90}});
    EXPECT_EQ(decode_value(data, TagType::int_, at(1)), Value{std::int64_t{90}});
    // The seed-style integer "Real": as a real tag it is a tiny subnormal.
    const Value real = decode_value(data, TagType::real, at(3));
    ASSERT_TRUE(std::holds_alternative<float>(real));
    EXPECT_EQ(std::bit_cast<std::uint32_t>(std::get<float>(real)), 0x0001016Cu);
    EXPECT_NEAR(std::get<float>(real) / 9.2346e-41f, 1.0f, 1e-4f);
    EXPECT_EQ(decode_value(data, TagType::dint, at(3)), Value{std::int64_t{65900}});
    EXPECT_EQ(decode_value(data, TagType::lint, at(7)), Value{std::int64_t{956000}});
}

TEST(Vectors, V2DecodesEveryTag) {
    const auto data = data_of(vectors::v2);
    EXPECT_EQ(decode_value(data, TagType::bit, at(0, 0)), Value{true});
    EXPECT_EQ(decode_value(data, TagType::bit, at(0, 3)), Value{false});
    EXPECT_EQ(decode_value(data, TagType::bit, at(0, 7)), Value{true});
    EXPECT_EQ(decode_value(data, TagType::word, at(1)), Value{std::uint64_t{90}});
    EXPECT_EQ(decode_value(data, TagType::real, at(3)), Value{65900.0f});
    EXPECT_EQ(decode_value(data, TagType::lint, at(7)), Value{std::int64_t{956000}});
}

TEST(Vectors, V2EncodesFromItsValues) {
    std::vector<std::byte> data(15);
    const bool bits[8] = {true, true, true, false, false, true, true, true};
    for (std::uint8_t b = 0; b < 8; ++b) encode_value(data, TagType::bit, at(0, b), bits[b]);
    encode_value(data, TagType::word, at(1), std::uint64_t{90});
    encode_value(data, TagType::real, at(3), 65900.0f);
    encode_value(data, TagType::lint, at(7), std::int64_t{956000});
    EXPECT_EQ(to_hex(data), to_hex(data_of(vectors::v2)));
}

TEST(Vectors, V3DecodesEveryTag) {
    const auto data = data_of(vectors::v3);
    EXPECT_EQ(decode_value(data, TagType::real, at(0)), Value{0.0f});
    EXPECT_EQ(decode_value(data, TagType::real, at(4)), Value{180.0f});
    EXPECT_EQ(decode_value(data, TagType::real, at(8)), Value{109.0f});
    EXPECT_EQ(decode_value(data, TagType::real, at(12)), Value{110.0f});
}

struct Scalar {
    TagType type;
    Value value;
    std::string_view hex;
};

// docs/protocol.md §8 V6.
const Scalar v6[] = {
    {TagType::int_, std::int64_t{-2}, "feff"},
    {TagType::word, std::uint64_t{65535}, "ffff"},
    {TagType::dint, std::int64_t{-100000}, "6079feff"},
    {TagType::udint, std::uint64_t{3000000000}, "005ed0b2"},
    {TagType::real, 1.5f, "0000c03f"},
    {TagType::real, -273.15f, "339388c3"},
    {TagType::lreal, 1.0, "000000000000f03f"},
    {TagType::lreal, 65900.0, "00000000c016f040"},
    {TagType::lint, std::int64_t{-2}, "feffffffffffffff"},
};

constexpr std::uint16_t offsets[] = {0, 1, 2, 3, 5, 7};

TEST(Vectors, V6ScalarsEncodeAtUnalignedOffsets) {
    for (const Scalar& s : v6) {
        for (std::uint16_t offset : offsets) {
            std::vector<std::byte> data(20, std::byte{0xA5});
            encode_value(data, s.type, at(offset), s.value);
            const std::size_t size = plan::size_of(s.type);
            EXPECT_EQ(to_hex(std::span(data).subspan(offset, size)), s.hex)
                << plan::to_string(s.type) << " at " << offset;
            // Every other byte keeps its value.
            for (std::size_t i = 0; i < data.size(); ++i) {
                if (i >= offset && i < offset + size) continue;
                EXPECT_EQ(data[i], std::byte{0xA5}) << "byte " << i;
            }
        }
    }
}

TEST(Vectors, V6ScalarsDecodeAtUnalignedOffsets) {
    for (const Scalar& s : v6) {
        const auto bytes = from_hex(s.hex);
        for (std::uint16_t offset : offsets) {
            std::vector<std::byte> data(20, std::byte{0x5A});
            std::copy(bytes.begin(), bytes.end(), data.begin() + offset);
            const Value decoded = decode_value(data, s.type, at(offset));
            EXPECT_EQ(decoded, s.value) << plan::to_string(s.type) << " at " << offset;
        }
    }
}

TEST(Vectors, V6ScalarsDecodeAtTheEndOfTheData) {
    for (const Scalar& s : v6) {
        const auto bytes = from_hex(s.hex);
        std::vector<std::byte> data(3, std::byte{0});
        data.insert(data.end(), bytes.begin(), bytes.end());
        EXPECT_EQ(decode_value(data, s.type, at(3)), s.value) << plan::to_string(s.type);
    }
}

TEST(DataTypes, ByteIsUnsigned) {
    const std::vector<std::byte> data{std::byte{0x00}, std::byte{0xFF}};
    EXPECT_EQ(decode_value(data, TagType::byte, at(1)), Value{std::uint64_t{255}});
    std::vector<std::byte> out(2);
    encode_value(out, TagType::byte, at(1), std::uint64_t{200});
    EXPECT_EQ(to_hex(out), "00c8");
}

TEST(DataTypes, IntAndDintExtremes) {
    std::vector<std::byte> data(7);
    encode_value(data, TagType::int_, at(1), std::int64_t{-32768});
    encode_value(data, TagType::dint, at(3), std::int64_t{2147483647});
    EXPECT_EQ(to_hex(data), "000080ffffff7f");
    EXPECT_EQ(decode_value(data, TagType::int_, at(1)), Value{std::int64_t{-32768}});
    EXPECT_EQ(decode_value(data, TagType::dint, at(3)), Value{std::int64_t{2147483647}});
    EXPECT_EQ(decode_value(data, TagType::udint, at(3)), Value{std::uint64_t{0x7FFFFFFF}});
}

TEST(DataTypes, RealKeepsNanAndInfinity) {
    std::vector<std::byte> data = from_hex("0000c07f0000807f000080ff");
    EXPECT_TRUE(std::isnan(std::get<float>(decode_value(data, TagType::real, at(0)))));
    EXPECT_EQ(decode_value(data, TagType::real, at(4)),
              Value{std::numeric_limits<float>::infinity()});
    EXPECT_EQ(decode_value(data, TagType::real, at(8)),
              Value{-std::numeric_limits<float>::infinity()});
}

TEST(DataTypes, LintExtremes) {
    std::vector<std::byte> data(9);
    encode_value(data, TagType::lint, at(1), std::numeric_limits<std::int64_t>::min());
    EXPECT_EQ(to_hex(data), "000000000000000080");
    EXPECT_EQ(decode_value(data, TagType::lint, at(1)),
              Value{std::numeric_limits<std::int64_t>::min()});
}

TEST(Bits, BitZeroIsTheLeastSignificant) {
    const std::vector<std::byte> data{std::byte{0x01}, std::byte{0x80}};
    EXPECT_EQ(decode_value(data, TagType::bit, at(0, 0)), Value{true});
    EXPECT_EQ(decode_value(data, TagType::bit, at(0, 7)), Value{false});
    EXPECT_EQ(decode_value(data, TagType::bit, at(1, 0)), Value{false});
    EXPECT_EQ(decode_value(data, TagType::bit, at(1, 7)), Value{true});
}

TEST(Bits, SettingABitChangesOnlyThatBit) {
    std::vector<std::byte> data{std::byte{0x00}, std::byte{0x24}, std::byte{0x00}};
    encode_value(data, TagType::bit, at(1, 3), true);
    EXPECT_EQ(to_hex(data), "002c00");
    encode_value(data, TagType::bit, at(1, 3), true);
    EXPECT_EQ(to_hex(data), "002c00");
}

TEST(Bits, ClearingABitChangesOnlyThatBit) {
    std::vector<std::byte> data{std::byte{0xFF}, std::byte{0xFF}, std::byte{0xFF}};
    encode_value(data, TagType::bit, at(1, 3), false);
    EXPECT_EQ(to_hex(data), "fff7ff");
    encode_value(data, TagType::bit, at(1, 7), false);
    EXPECT_EQ(to_hex(data), "ff77ff");
}

TEST(Bits, NonAdjacentBitsAreKept) {
    // §7: packing that flushes a byte only after "the last configured bit" breaks here.
    std::vector<std::byte> data(1);
    encode_value(data, TagType::bit, at(0, 1), true);
    encode_value(data, TagType::bit, at(0, 6), true);
    EXPECT_EQ(to_hex(data), "42");
    encode_value(data, TagType::bit, at(0, 1), false);
    EXPECT_EQ(to_hex(data), "40");
}

TEST(Bits, NonBoolValuesSetTheBitWhenNonZero) {
    std::vector<std::byte> data(1);
    encode_value(data, TagType::bit, at(0, 2), std::int64_t{5});
    EXPECT_EQ(to_hex(data), "04");
    encode_value(data, TagType::bit, at(0, 2), 0.0);
    EXPECT_EQ(to_hex(data), "00");
}

TEST(Conversion, IntegerValueOfARealTagIsEncodedAsIeee) {
    // §7: REAL 65900 is 00 B6 80 47, not the integer bytes 6C 01 01 00.
    std::vector<std::byte> data(4);
    encode_value(data, TagType::real, at(0), std::int64_t{65900});
    EXPECT_EQ(to_hex(data), "00b68047");
    encode_value(data, TagType::dint, at(0), std::int64_t{65900});
    EXPECT_EQ(to_hex(data), "6c010100");
}

TEST(Conversion, OtherAlternativesConvertAsByStaticCast) {
    std::vector<std::byte> data(8);
    encode_value(data, TagType::lreal, at(0), 1.5f);
    EXPECT_EQ(decode_value(data, TagType::lreal, at(0)), Value{1.5});
    encode_value(data, TagType::dint, at(0), 2.9);
    EXPECT_EQ(decode_value(data, TagType::dint, at(0)), Value{std::int64_t{2}});
    encode_value(data, TagType::word, at(0), std::int64_t{65535});
    EXPECT_EQ(decode_value(data, TagType::word, at(0)), Value{std::uint64_t{65535}});
    encode_value(data, TagType::byte, at(0), true);
    EXPECT_EQ(decode_value(data, TagType::byte, at(0)), Value{std::uint64_t{1}});
}

TEST(Conversion, FloatingValuesOutOfRangeSaturateAndNanIsZero) {
    std::vector<std::byte> data(2);
    encode_value(data, TagType::int_, at(0), 1e20);
    EXPECT_EQ(decode_value(data, TagType::int_, at(0)), Value{std::int64_t{32767}});
    encode_value(data, TagType::word, at(0), -5.0f);
    EXPECT_EQ(decode_value(data, TagType::word, at(0)), Value{std::uint64_t{0}});
    encode_value(data, TagType::int_, at(0), std::numeric_limits<double>::quiet_NaN());
    EXPECT_EQ(decode_value(data, TagType::int_, at(0)), Value{std::int64_t{0}});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
