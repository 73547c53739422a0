#include "eip2mqtt/core/command/command_nak.hpp"

#include <gtest/gtest.h>

#include "eip2mqtt/core/command/decode.hpp"
#include "eip2mqtt/core/command/encode.hpp"
#include "tests/core/command/command_vectors.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

using test::from_hex;
namespace v = test::command_vectors;

TEST(CommandNak, AMalformedReadGetsTheVectorNak) {
    const auto request = from_hex(v::c14_read_without_cells);
    const auto decoded = decode_request(request);
    ASSERT_FALSE(decoded.ok());
    const auto reply = make_nak(request, decoded.error());
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(test::to_hex(encode(reply->header, reply->nak)), v::c15_nak);
}

TEST(CommandNak, EchoesFlagRequestIdAndAtMostSixteenBytes) {
    auto request = from_hex(v::c11_write_request);
    request[1] = std::byte{0x5A};
    const auto reply = make_nak(request, DecodeError::truncated);
    ASSERT_TRUE(reply.has_value());
    EXPECT_EQ(reply->header.flag, 0x5A);
    EXPECT_EQ(reply->header.request_id, 9);
    EXPECT_EQ(reply->nak.offending.size(), nak_echo_size);
    EXPECT_EQ(reply->nak.key.exchange_id, 7u);
    EXPECT_EQ(reply->nak.error, "truncated");
}

TEST(CommandNak, NothingIsAnsweredWithoutAHeaderOrToAResponse) {
    EXPECT_FALSE(make_nak(from_hex("0900"), DecodeError::no_header).has_value());
    EXPECT_FALSE(make_nak(from_hex(v::c15_nak), DecodeError::not_a_request).has_value());
    EXPECT_FALSE(
        make_nak(from_hex(v::c2_retrieve_config_response), DecodeError::not_a_request).has_value());
}

TEST(CommandNak, AResponseOrANakWithABadVersionOrLengthIsNotAnswered) {
    // §9.5: responses and NAKs are never answered, whatever else is wrong with them; two
    // responders would otherwise NAK each other's NAKs for ever.
    for (const auto hex : {v::c15_nak, v::c2_retrieve_config_response}) {
        auto bad_version = from_hex(hex);
        bad_version[4] = std::byte{2};
        EXPECT_FALSE(make_nak(bad_version, decode_request(bad_version).error()).has_value());
        auto bad_length = from_hex(hex);
        bad_length[6] = std::byte{0xFF};
        EXPECT_FALSE(make_nak(bad_length, decode_request(bad_length).error()).has_value());
    }
    // A request with a bad version is still NAKed.
    auto request = from_hex(v::c9_read_request);
    request[4] = std::byte{2};
    EXPECT_TRUE(make_nak(request, DecodeError::wrong_version).has_value());
}

TEST(CommandNak, ANakIsNeverLargerThanFiftyTwoBytes) {
    // The longest reason name bounds a NAK: a reflected NAK cannot amplify much.
    for (const auto error : all_decode_errors) {
        const auto reply = make_nak(from_hex(v::c9_read_request), error);
        if (!reply) continue;
        EXPECT_LE(encode(reply->header, reply->nak).size(), 52u) << to_string(error);
    }
}

TEST(DecodeErrors, NakCodesAreDistinctAndRoundTrip) {
    for (const auto error : all_decode_errors) {
        const auto code = nak_code(error);
        if (!code) continue;
        EXPECT_EQ(decode_error_of_nak_code(*code), error) << to_string(error);
    }
    EXPECT_FALSE(decode_error_of_nak_code(0).has_value());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
