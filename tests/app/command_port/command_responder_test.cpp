// The command responder without a socket (docs/protocol.md §9): who is answered, how often,
// NAKs, and writes answered only once their result is in.

#include "eip2mqtt/app/command_port/command_responder.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

#include "eip2mqtt/core/command/encode.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/core/command/command_vectors.hpp"
#include "tests/core/vectors.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/log_capture.hpp"
#include "tests/support/fakes/recording_write_handler.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::command::CommandStatus;
using core::command::PduType;
namespace v = test::command_vectors;
using test::RecordingWriteHandler;

constexpr std::uint32_t requester = 0x0A140007;  // 10.20.0.7
constexpr std::uint32_t stranger = 0x0A150007;   // 10.21.0.7

class CommandResponderTest : public ::testing::Test {
protected:
    CommandResponderTest() {
        views_.push_back(
            {&plan_, core::command::ExchangeMode::produced, core::command::ExchangeState::active});
        views_[0].image = image_;
        views_[0].writable = true;
    }

    /// The requester's subnet allowed and trusted (answered without proving its address).
    CommandPolicy policy(bool writes = false, std::uint32_t rate = 100) const {
        const auto subnet = *core::net::parse_subnet("10.20.0.0/24");
        return {{subnet}, writes, rate, {subnet}, 0};
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

    void ask(CommandResponder& responder, std::string_view hex, std::uint32_t from = requester,
             core::MonoTime now = t0) {
        responder.on_datagram(test::from_hex(hex), {from, 4000}, now, core::WallTime{});
    }

    core::command::Response last() const {
        EXPECT_FALSE(sent_.empty());
        return core::command::decode_response(sent_.back().bytes).value();
    }

    struct Sent {
        std::vector<std::byte> bytes;
        adapters::udp::Endpoint to;
    };
    static constexpr core::MonoTime t0 = core::MonoTime{} + 1h;
    core::plan::ExchangePlan plan_ = [] {
        auto plan = test::test_plan("out", core::plan::Direction::produce, 8,
                                    {test::test_tag("SPEED", 4, core::plan::TagType::word, true)});
        plan.spec.producer_id = *core::wire::parse_producer_id("10.0.0.5");
        plan.spec.exchange_id = 7;
        return plan;
    }();
    std::vector<std::byte> image_ = std::vector<std::byte>(8);
    std::vector<core::command::ExchangeView> views_;
    std::vector<Sent> sent_;
    RecordingWriteHandler writes_;
};

TEST_F(CommandResponderTest, AnAllowedRequesterGetsTheResponseAtItsAddressAndPort) {
    auto responder = make(policy());
    ask(responder, v::c3_capabilities_request);
    ASSERT_EQ(sent_.size(), 1u);
    EXPECT_EQ(sent_[0].to.address, requester);
    EXPECT_EQ(sent_[0].to.port, 4000);
    EXPECT_EQ(last().header.type, PduType::capabilities_response);
    EXPECT_EQ(responder.counters().requests[request_index(PduType::capabilities_request)], 1u);
}

TEST_F(CommandResponderTest, ASourceOutsideAllowGetsNothingAndIsCounted) {
    auto responder = make(policy());
    ask(responder, v::c3_capabilities_request, stranger);
    ask(responder, v::c14_read_without_cells, stranger);  // not even a NAK
    EXPECT_TRUE(sent_.empty());
    EXPECT_EQ(responder.counters().refused, 2u);
    // A reload's new allow list applies to the next datagram.
    auto wider = policy();
    wider.allow.push_back(*core::net::parse_subnet("10.21.0.0/16"));
    responder.set_policy(wider);
    ask(responder, v::c3_capabilities_request, stranger);
    EXPECT_EQ(sent_.size(), 1u);
}

TEST_F(CommandResponderTest, AFloodBeyondTheRateLimitIsDroppedAndCounted) {
    auto responder = make(policy(false, 10));
    for (int i = 0; i < 50; ++i) ask(responder, v::c3_capabilities_request);
    // One second's worth at once, then nothing until tokens come back.
    EXPECT_EQ(sent_.size(), 10u);
    EXPECT_EQ(responder.counters().dropped, 40u);
    ask(responder, v::c3_capabilities_request, requester, t0 + 200ms);
    EXPECT_EQ(sent_.size(), 11u);  // 200 ms at 10/s: two tokens back, one used here
}

TEST_F(CommandResponderTest, NaksGoToWhatCannotBeUnderstoodAndNothingToResponses) {
    auto responder = make(policy());
    ask(responder, v::c14_read_without_cells);
    ASSERT_EQ(sent_.size(), 1u);
    EXPECT_EQ(test::to_hex(sent_[0].bytes), v::c15_nak);
    ask(responder, v::c15_nak);
    ask(responder, v::c2_retrieve_config_response);
    ask(responder, "0900");
    EXPECT_EQ(sent_.size(), 1u);
    EXPECT_EQ(
        responder.counters().naks[static_cast<std::size_t>(core::command::DecodeError::malformed)],
        1u);
    EXPECT_EQ(responder.counters().ignored, 3u);
}

TEST_F(CommandResponderTest, AResponseOrANakWithABadVersionOrLengthIsNotAnswered) {
    auto responder = make(policy());
    for (const auto hex :
         {v::c15_nak, v::c2_retrieve_config_response, v::c4_capabilities_response}) {
        auto bad_version = test::from_hex(hex);
        bad_version[4] = std::byte{7};
        responder.on_datagram(bad_version, {requester, 4000}, t0, core::WallTime{});
        auto bad_length = test::from_hex(hex);
        bad_length[6] = std::byte{0xFF};
        responder.on_datagram(bad_length, {requester, 4000}, t0, core::WallTime{});
    }
    EXPECT_TRUE(sent_.empty());
    EXPECT_EQ(responder.counters().ignored, 6u);
}

TEST_F(CommandResponderTest, WritesOffAreNotPermittedAndReachNoExchange) {
    auto responder = make(policy(false));
    ask(responder, v::c11_write_request);
    EXPECT_TRUE(writes_.requests.empty());
    EXPECT_EQ(last().header.status, static_cast<std::uint8_t>(CommandStatus::not_permitted));
    EXPECT_EQ(responder.counters().errors, 1u);
}

TEST_F(CommandResponderTest, AWriteIsAnsweredOnlyWhenItsResultComes) {
    auto responder = make(policy(true));
    ask(responder, v::c11_write_request);
    EXPECT_TRUE(sent_.empty());
    ASSERT_EQ(writes_.requests.size(), 1u);
    const auto& request = writes_.requests[0];
    EXPECT_EQ(request.reply.via, WriteOrigin::commands);
    const auto& write = std::get<ExchangeWrite>(request.outcome);
    EXPECT_EQ(write.producer, &plan_);
    ASSERT_EQ(write.writes.size(), 1u);
    EXPECT_EQ(std::get<std::uint64_t>(write.writes[0].value), 1000u);
    EXPECT_EQ(responder.pending_writes(), 1u);

    request.reply.origin->write_result(request.reply, std::nullopt);
    ASSERT_EQ(sent_.size(), 1u);
    EXPECT_EQ(sent_[0].to.address, requester);
    const auto response = last();
    EXPECT_EQ(response.header.type, PduType::write_response);
    EXPECT_EQ(response.header.request_id, 9);
    EXPECT_EQ(response.header.status, 0);
    EXPECT_EQ(responder.pending_writes(), 0u);
    // A result for a write it no longer waits for changes nothing.
    request.reply.origin->write_result(request.reply, std::nullopt);
    EXPECT_EQ(sent_.size(), 1u);
}

TEST_F(CommandResponderTest, AWriteIsAnsweredWithItsClocksTimeWhenItsResultComes) {
    test::FakeClock clock;
    CommandResponder responder(
        policy(true), {}, [this](core::MonoTime, core::WallTime) { return views_; },
        [this](std::span<const std::byte> bytes, const adapters::udp::Endpoint& to) {
            sent_.push_back({{bytes.begin(), bytes.end()}, to});
            return true;
        },
        &writes_, clock);
    ask(responder, v::c11_write_request);
    ASSERT_EQ(writes_.requests.size(), 1u);
    clock.advance(1500ms);  // the result comes later: the answer says when
    const auto& request = writes_.requests[0];
    request.reply.origin->write_result(request.reply, std::nullopt);
    const auto response = last();  // held: the PDU is a part of it
    const auto& pdu = std::get<core::command::DataPdu>(response.body);
    EXPECT_EQ(pdu.time_s, core::wire_time(clock.wall()).seconds);
    EXPECT_EQ(pdu.time_ns, 500000000u);
}

TEST_F(CommandResponderTest, AWriteRefusedWhenStagedIsRejectedAndOneLostLaterFailed) {
    auto responder = make(policy(true));
    writes_.refuse = true;
    ask(responder, v::c11_write_request);
    EXPECT_EQ(last().header.status, static_cast<std::uint8_t>(CommandStatus::rejected));
    writes_.refuse = false;
    ask(responder, v::c11_write_request);
    const auto& request = writes_.requests.at(0);
    request.reply.origin->write_result(request.reply, "reloaded");
    EXPECT_EQ(last().header.status, static_cast<std::uint8_t>(CommandStatus::failed));
    EXPECT_EQ(responder.counters().errors, 2u);
    EXPECT_EQ(responder.pending_writes(), 0u);
}

TEST_F(CommandResponderTest, TheFirstRefusalIsLoggedAndTheRestSummarisedByTheTick) {
    test::LogCapture log;
    auto responder = make(policy());
    for (int i = 0; i < 5; ++i) ask(responder, v::c3_capabilities_request, stranger);
    auto lines = log.lines();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("outside eip.commands.allow (10.21.0.7:4000)"), std::string::npos);
    // The four others wait for the interval; the tick then writes one line for them.
    responder.flush_log(t0 + 30s);
    EXPECT_TRUE(log.lines().empty());
    responder.flush_log(t0 + 61s);
    lines = log.lines();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("4 datagrams refused, dropped or NAKed in the last 60 s; 5 refused"),
              std::string::npos)
        << lines[0];
    responder.flush_log(t0 + 130s);  // nothing new: no line
    EXPECT_TRUE(log.lines().empty());
}

TEST_F(CommandResponderTest, WithoutAWriteHandlerWritesAreNeverStaged) {
    CommandResponder responder(
        policy(true), {}, [this](core::MonoTime, core::WallTime) { return views_; },
        [this](std::span<const std::byte> bytes, const adapters::udp::Endpoint& to) {
            sent_.push_back({{bytes.begin(), bytes.end()}, to});
            return true;
        },
        nullptr);
    ask(responder, v::c11_write_request);
    EXPECT_EQ(last().header.status, static_cast<std::uint8_t>(CommandStatus::not_permitted));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
