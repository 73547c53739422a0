// The command responder against reflection, amplification and forged sources (docs/protocol.md
// §9.7): a requester that has not proved its address never gets more bytes than it sent and
// writes nothing; each source has its own rate limit, and the unproven a budget of their own.

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "eip2mqtt/app/command_port/command_responder.hpp"
#include "eip2mqtt/core/command/address_proof.hpp"
#include "eip2mqtt/core/command/encode.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/core/command/command_vectors.hpp"
#include "tests/core/vectors.hpp"
#include "tests/support/fakes/recording_write_handler.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::command::CommandStatus;
using core::command::PduType;
namespace v = test::command_vectors;
using test::RecordingWriteHandler;

constexpr std::uint32_t requester = 0x0A140007;  // 10.20.0.7
constexpr std::uint32_t neighbour = 0x0A140008;  // 10.20.0.8
constexpr core::MonoTime t0 = core::MonoTime{} + 1h;

class CommandProofTest : public ::testing::Test {
protected:
    CommandProofTest() {
        auto plan = test::test_plan("out", core::plan::Direction::produce, 8,
                                    {test::test_tag("SPEED", 4, core::plan::TagType::word, true)});
        plan.spec.producer_id = *core::wire::parse_producer_id("10.0.0.5");
        plan.spec.exchange_id = 7;
        plan_ = std::move(plan);
        views_.push_back(
            {&plan_, core::command::ExchangeMode::produced, core::command::ExchangeState::active});
        views_[0].image = image_;
        views_[0].writable = true;
    }

    CommandPolicy policy(bool writes = false, std::uint32_t rate = 100,
                         std::uint32_t per_source = 0) const {
        return {{*core::net::parse_subnet("10.20.0.0/24")}, writes, rate, {}, per_source};
    }

    CommandResponder make(CommandPolicy policy) {
        return CommandResponder(
            std::move(policy), {}, [this](core::MonoTime, core::WallTime) { return views_; },
            [this](std::span<const std::byte> bytes, const adapters::udp::Endpoint& to) {
                sent_.push_back({{bytes.begin(), bytes.end()}, to});
                return true;
            },
            &writes_);
    }

    void ask(CommandResponder& responder, std::vector<std::byte> bytes,
             std::uint32_t from = requester, core::MonoTime now = t0) {
        responder.on_datagram(bytes, {from, 4000}, now, core::WallTime{});
    }

    /// `hex` carrying the token of `from`.
    static std::vector<std::byte> proven(const CommandResponder& responder, std::string_view hex,
                                         std::uint32_t from = requester) {
        auto bytes = test::from_hex(hex);
        core::command::carry_token(bytes, responder.token_for_test(from, t0));
        return bytes;
    }

    struct Sent {
        std::vector<std::byte> bytes;
        adapters::udp::Endpoint to;
    };
    core::plan::ExchangePlan plan_;
    std::vector<std::byte> image_ = std::vector<std::byte>(8);
    std::vector<core::command::ExchangeView> views_;
    std::vector<Sent> sent_;
    RecordingWriteHandler writes_;
};

TEST_F(CommandProofTest, AnUnprovenRequesterGetsNoMoreBytesThanItSent) {
    auto responder = make(policy());
    // A 12-byte Summary whose answer is larger: a 12-byte challenge, with the token.
    const auto summary = test::from_hex(v::c5_summary_request);
    ask(responder, summary);
    ASSERT_EQ(sent_.size(), 1u);
    EXPECT_LE(sent_[0].bytes.size(), summary.size());
    EXPECT_EQ(core::command::challenge_token(sent_[0].bytes),
              responder.token_for_test(requester, t0));
    EXPECT_EQ(responder.counters().challenged, 1u);
    EXPECT_EQ(responder.counters().requests[request_index(PduType::summary_request)], 0u);
    // Every request type: never a byte more than asked with.
    for (const auto hex :
         {v::c1_retrieve_config_request, v::c3_capabilities_request, v::c7_statistics_request,
          v::c9_read_request, v::c14_read_without_cells, std::string_view("0900050001000800")}) {
        sent_.clear();
        const auto request = test::from_hex(hex);
        ask(responder, request);
        for (const auto& sent : sent_) EXPECT_LE(sent.bytes.size(), request.size()) << hex;
    }
}

TEST_F(CommandProofTest, TheTokenEchoedProvesTheAddressAndGetsTheWholeAnswer) {
    auto responder = make(policy());
    ask(responder, test::from_hex(v::c5_summary_request));
    const auto token = core::command::challenge_token(sent_.at(0).bytes).value();
    auto again = test::from_hex(v::c5_summary_request);
    core::command::carry_token(again, token);
    ask(responder, again, requester, t0 + 1s);
    ASSERT_EQ(sent_.size(), 2u);
    const auto response = core::command::decode_response(sent_[1].bytes);
    ASSERT_TRUE(response.ok());
    EXPECT_EQ(response->header.type, PduType::summary_response);
    EXPECT_EQ(response->header.status, 0);
    EXPECT_EQ(responder.counters().requests[request_index(PduType::summary_request)], 1u);
    // Another address carrying that token proves nothing: it is the requester's.
    ask(responder, again, neighbour, t0 + 1s);
    EXPECT_EQ(core::command::challenge_token(sent_.back().bytes),
              responder.token_for_test(neighbour, t0));
}

TEST_F(CommandProofTest, AForgedWriteFromAnAllowedAddressIsNotApplied) {
    auto responder = make(policy(true));
    ask(responder, test::from_hex(v::c11_write_request));
    EXPECT_TRUE(writes_.requests.empty());
    ASSERT_EQ(sent_.size(), 1u);
    const auto header = core::command::decode_header(sent_[0].bytes);
    ASSERT_TRUE(header.ok());
    EXPECT_EQ(header->type, PduType::write_response);
    EXPECT_EQ(header->status, static_cast<std::uint8_t>(CommandStatus::prove_address));
    // With the token, the same write is staged.
    ask(responder, proven(responder, v::c11_write_request));
    EXPECT_EQ(writes_.requests.size(), 1u);
}

TEST_F(CommandProofTest, ANakLargerThanItsRequestGoesOnlyToAProvenRequester) {
    auto responder = make(policy());
    ask(responder, test::from_hex(v::c14_read_without_cells));
    EXPECT_TRUE(sent_.empty());
    EXPECT_EQ(responder.counters().ignored, 1u);
    ask(responder, proven(responder, v::c14_read_without_cells));
    ASSERT_EQ(sent_.size(), 1u);
    EXPECT_EQ(core::command::decode_response(sent_[0].bytes)->header.type, PduType::nak);
}

TEST_F(CommandProofTest, OneSourceOverItsLimitDoesNotStarveAnother) {
    auto responder = make(policy(false, 100, 5));
    for (int i = 0; i < 50; ++i) ask(responder, proven(responder, v::c5_summary_request));
    EXPECT_EQ(sent_.size(), 5u);
    EXPECT_EQ(responder.counters().dropped_per_source, 45u);
    EXPECT_EQ(responder.counters().dropped, 45u);
    for (int i = 0; i < 5; ++i) {
        ask(responder, proven(responder, v::c5_summary_request, neighbour), neighbour);
    }
    EXPECT_EQ(sent_.size(), 10u);
}

TEST_F(CommandProofTest, ForgedSourcesCannotSpendTheBudgetOfProvenRequesters) {
    auto responder = make(policy(false, 10));
    // Forged sources all over the allowed subnet, none able to carry its token.
    for (std::uint32_t host = 1; host < 200; ++host) {
        ask(responder, test::from_hex(v::c5_summary_request), 0x0A140000 | host);
    }
    EXPECT_EQ(responder.counters().challenged, 10u);
    const auto before = sent_.size();
    ask(responder, proven(responder, v::c5_summary_request));
    ASSERT_EQ(sent_.size(), before + 1);
    EXPECT_EQ(core::command::decode_response(sent_.back().bytes)->header.type,
              PduType::summary_response);
}

TEST_F(CommandProofTest, AWriteTheValueChecksRefuseGoesToTheWriteHandlerWithItsReason) {
    auto plan = plan_;
    plan.tags[0].spec.mutable_extras().max = 100;
    views_[0].plan = &plan;
    auto responder = make(policy(true));
    // c11 writes 1000 to the word at 4: over the tag's max of 100.
    ask(responder, proven(responder, v::c11_write_request));
    ASSERT_EQ(writes_.requests.size(), 1u);
    const auto& request = writes_.requests[0];
    const auto* rejection = std::get_if<core::write::WriteRejection>(&request.outcome);
    ASSERT_NE(rejection, nullptr);
    EXPECT_EQ(rejection->error, core::write::WriteError::above_max);
    EXPECT_EQ(request.reply.via, WriteOrigin::commands);
}

TEST_F(CommandProofTest, AllowWrittenEmptyAnswersNobody) {
    core::config::Config config;
    config.eip.bind = "127.0.0.1";
    config.eip.commands.allow = std::vector<core::net::Subnet>{};
    EXPECT_TRUE(command_policy(config).allow.empty());
    auto responder = make(command_policy(config));
    ask(responder, test::from_hex(v::c5_summary_request), 0x7F000001);
    EXPECT_TRUE(sent_.empty());
    EXPECT_EQ(responder.counters().refused, 1u);
    // Not written: the subnets of eip.bind's interfaces.
    config.eip.commands.allow.reset();
    EXPECT_FALSE(command_policy(config).allow.empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
