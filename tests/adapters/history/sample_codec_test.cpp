// The journal's sample encoding: every value kind comes back as it went in, small
// values stay small, and bytes that are not an encoding of ours are an error, never a crash.

#include "eip2mqtt/adapters/history/sample_codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::history {
namespace EIP2MQTT_THIS_FILE {

using core::plan::Value;

TEST(SampleCodec, EveryKindComesBackAsItWentIn) {
    const std::vector<JournaledSample> samples{
        {0, Value{true}},
        {1, Value{false}},
        {2, Value{std::int64_t{-1}}},
        {3, Value{std::numeric_limits<std::int64_t>::min()}},
        {4, Value{std::numeric_limits<std::int64_t>::max()}},
        {5, Value{std::numeric_limits<std::uint64_t>::max()}},
        {6, Value{1.1f}},
        {70000, Value{-2.5e300}},
        {7, Value{std::numeric_limits<double>::quiet_NaN()}},
        {8, core::plan::make_text("B-\xC3\xA9 17")},
        {9, core::plan::make_text("")},
        {10, core::plan::make_list({Value{1.5f}, Value{-2.0f}, Value{0.0f}})},
        {11, core::plan::make_list({Value{true}, Value{false}})},
    };
    std::string bytes;
    encode_samples(samples, bytes);
    const auto decoded = decode_samples(bytes);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    ASSERT_EQ(decoded.value().size(), samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        EXPECT_EQ(decoded.value()[i].tag, samples[i].tag);
        EXPECT_TRUE(core::plan::same_value(decoded.value()[i].value, samples[i].value)) << i;
    }
}

TEST(SampleCodec, ASmallIntegerTakesThreeBytes) {
    std::string bytes;
    const std::vector<JournaledSample> one{{5, Value{std::int64_t{-60}}}};
    encode_samples(one, bytes);
    EXPECT_EQ(bytes.size(), 3u);  // index, kind, zigzag value
}

TEST(SampleCodec, BytesThatAreNotOursAreAnError) {
    std::string bytes;
    const std::vector<JournaledSample> one{{1, Value{2.0}}};
    encode_samples(one, bytes);
    for (std::size_t cut = 1; cut < bytes.size(); ++cut) {
        EXPECT_FALSE(decode_samples(bytes.substr(0, cut)).ok()) << cut;
    }
    EXPECT_FALSE(decode_samples(std::string("\x01\x09", 2)).ok());  // unknown kind
    EXPECT_FALSE(decode_samples(std::string(11, '\xff')).ok());     // index over 64 bits
    EXPECT_FALSE(decode_samples(std::string("\x01\x06\x05"
                                            "ab",
                                            5))
                     .ok());                                                    // text cut short
    EXPECT_FALSE(decode_samples(std::string("\x01\x07\x02\x00", 4)).ok());      // array cut short
    EXPECT_FALSE(decode_samples(std::string("\x01\x07\x01\x07\x00", 5)).ok());  // array in one
    EXPECT_FALSE(decode_samples(std::string("\x01\x07\xff\xff\x7f", 5)).ok());  // huge count
    EXPECT_TRUE(decode_samples("").ok());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::history
