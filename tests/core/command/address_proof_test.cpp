#include "eip2mqtt/core/command/address_proof.hpp"

#include <gtest/gtest.h>

#include "eip2mqtt/core/command/command_status.hpp"
#include "eip2mqtt/core/command/decode.hpp"
#include "eip2mqtt/core/command/encode.hpp"
#include "tests/core/command/command_vectors.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

constexpr ProofKey key{0x0123456789abcdefULL, 0xfedcba9876543210ULL};
constexpr std::uint32_t requester = 0x0A140007;  // 10.20.0.7
constexpr MonoTime t0 = MonoTime{} + 24h;

PduHeader carrying(std::uint32_t token) {
    PduHeader header;
    header.type = PduType::summary_request;
    header.flag = static_cast<std::uint8_t>(token >> 16);
    header.request_id = static_cast<std::uint16_t>(token);
    return header;
}

TEST(AddressProof, ATokenIs24BitsAndDependsOnAddressKeyAndPeriod) {
    const AddressProof proof(key);
    const auto token = proof.token(requester, t0);
    EXPECT_LE(token, 0xFFFFFFu);
    EXPECT_EQ(proof.token(requester, t0 + 1s), token);
    EXPECT_NE(proof.token(requester + 1, t0), token);
    EXPECT_NE(AddressProof({key[0], key[1] + 1}).token(requester, t0), token);
    EXPECT_NE(proof.token(requester, t0 + token_period), token);
}

TEST(AddressProof, ATokenProvesItsAddressForItsPeriodAndTheNextOnly) {
    const AddressProof proof(key);
    const auto header = carrying(proof.token(requester, t0));
    EXPECT_TRUE(proof.proves(header, requester, t0));
    EXPECT_TRUE(proof.proves(header, requester, t0 + token_period));
    EXPECT_FALSE(proof.proves(header, requester, t0 + 2 * token_period));
    EXPECT_FALSE(proof.proves(header, requester + 1, t0));
    EXPECT_FALSE(proof.proves(carrying(0), requester, t0));
}

TEST(AddressProof, AChallengeIsNeverLargerThanItsRequestAndCarriesTheToken) {
    auto request = encode(carrying(0x1234), SummaryRequest{0});
    ASSERT_EQ(request.size(), 12u);
    const auto header = decode_request(request)->header;
    const auto answer = challenge(header, request.size(), 0xABCDEF);
    ASSERT_EQ(answer.size(), challenge_size);
    const auto decoded = decode_header(answer);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(decoded->type, PduType::summary_response);
    EXPECT_EQ(decoded->request_id, 0x1234);
    EXPECT_EQ(decoded->status, static_cast<std::uint8_t>(CommandStatus::prove_address));
    EXPECT_EQ(challenge_token(answer), 0xABCDEFu);
    // The 8-byte Capabilities request gets the header alone: no token, but no amplification.
    PduHeader capabilities;
    const auto short_answer = challenge(capabilities, header_size, 0xABCDEF);
    EXPECT_EQ(short_answer.size(), header_size);
    EXPECT_FALSE(challenge_token(short_answer).has_value());
}

TEST(AddressProof, C16IsTheChallengeToC5) {
    const auto request = test::from_hex(test::command_vectors::c5_summary_request);
    const auto header = decode_request(request)->header;
    EXPECT_EQ(test::to_hex(challenge(header, request.size(), 0xABCDEF)),
              test::command_vectors::c16_challenge);
    EXPECT_EQ(challenge_token(test::from_hex(test::command_vectors::c16_challenge)), 0xABCDEFu);
}

TEST(AddressProof, ARequesterCarriesTheTokenInFlagAndRequestId) {
    auto request = encode(carrying(0), SummaryRequest{0});
    carry_token(request, 0xABCDEF);
    const auto header = decode_request(request)->header;
    EXPECT_EQ(carried_token(header), 0xABCDEFu);
    EXPECT_EQ(header.flag, 0xAB);
    EXPECT_EQ(header.request_id, 0xCDEF);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
