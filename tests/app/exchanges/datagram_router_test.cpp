// The datagram router without a socket (docs/architecture.md "One datagram north"): each
// datagram reaches the exchange its key names, from the source it requires, and each one
// dropped on the way is counted under its reason. Time is passed in.

#include "eip2mqtt/app/exchanges/datagram_router.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "tests/app/support/json_tree_recorder.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;
using core::wire::DropReason;

constexpr std::uint32_t plc = 0x0A000001;       // 10.0.0.1
constexpr std::uint32_t intruder = 0x0A000063;  // 10.0.0.99

core::plan::ExchangePlan plan(std::string name, std::uint32_t exchange_id,
                              std::optional<std::uint32_t> source = std::nullopt) {
    core::plan::ExchangeSpec spec;
    spec.name = name;
    spec.direction = core::plan::Direction::consume;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = exchange_id;
    spec.length = 4;
    spec.source = source;
    spec.topic = std::move(name);
    core::plan::TagSpec tag;
    tag.name = "A";
    tag.address = {0, 0};
    tag.type = TagType::dint;
    spec.tags.push_back(tag);
    return core::plan::make_exchange_plan(std::move(spec), "plant");
}

std::vector<std::byte> datagram(std::uint32_t exchange_id, std::uint16_t rid, std::int64_t value,
                                std::size_t length = 4) {
    return test::DatagramBuilder("10.0.0.1", exchange_id, length)
        .request_id(rid)
        .set("0.0", TagType::dint, core::plan::Value{value})
        .build();
}

class DatagramRouterTest : public ::testing::Test {
protected:
    void add(core::plan::ExchangePlan p) {
        consumers_.push_back(std::make_unique<ExchangeConsumer>(std::move(p), uns_.northbound()));
        router_.set_consumers(consumers_);
    }
    void route(const std::vector<std::byte>& bytes, std::uint32_t from = plc,
               bool truncated = false) {
        now_ += 10ms;
        router_.route(bytes, {from, 18246}, truncated, now_);
    }
    /// The payloads published on `topic`, in order.
    std::vector<std::string> on(const std::string& topic) const { return uns_.publisher.on(topic); }
    std::uint64_t dropped(DropReason reason) const {
        return router_.counters().dropped_for(reason);
    }
    std::uint64_t dropped_in_all() const {
        std::uint64_t sum = 0;
        for (const auto n : router_.counters().dropped) sum += n;
        return sum;
    }

    core::MonoTime now_ = core::MonoTime{} + 1h;
    test::JsonTreeRecorder uns_;
    std::vector<std::unique_ptr<ExchangeConsumer>> consumers_;
    test::FakeClock clock_{core::WallTime{} + 1h};
    DatagramRouter router_{clock_};
};

TEST_F(DatagramRouterTest, EachDatagramReachesTheExchangeItsKeyNames) {
    add(plan("one", 1));
    add(plan("two", 2));
    route(datagram(2, 1, 22));
    route(datagram(1, 1, 11));
    EXPECT_EQ(router_.counters().datagrams, 2u);
    EXPECT_EQ(router_.counters().accepted, 2u);
    EXPECT_EQ(dropped_in_all(), 0u);
    ASSERT_EQ(on("plant/one/A").size(), 1u);
    ASSERT_EQ(on("plant/two/A").size(), 1u);
    EXPECT_NE(on("plant/one/A")[0].find("\"value\":11"), std::string::npos);
    EXPECT_NE(on("plant/two/A")[0].find("\"value\":22"), std::string::npos);
    EXPECT_EQ(consumers_[0]->exchange().counters().accepted, 1u);
    EXPECT_EQ(consumers_[1]->exchange().counters().accepted, 1u);
}

TEST_F(DatagramRouterTest, WhatCannotBeDecodedIsCountedUnderItsReasonAndReachesNoExchange) {
    add(plan("one", 1));
    route(datagram(1, 1, 11), plc, /*truncated=*/true);
    route(std::vector<std::byte>(31));  // shorter than a header
    auto not_data = datagram(1, 2, 11);
    not_data[0] = std::byte{0x0E};
    route(not_data);
    auto header_only = datagram(1, 3, 11);
    header_only.resize(32);
    route(header_only);
    EXPECT_EQ(dropped(DropReason::too_long), 1u);
    EXPECT_EQ(dropped(DropReason::too_short), 1u);
    EXPECT_EQ(dropped(DropReason::not_data_pdu), 1u);
    EXPECT_EQ(dropped(DropReason::no_data), 1u);
    EXPECT_EQ(dropped_in_all(), 4u);
    EXPECT_EQ(router_.counters().datagrams, 4u);
    EXPECT_EQ(router_.counters().accepted, 0u);
    EXPECT_EQ(consumers_[0]->exchange().counters().received, 0u);
    EXPECT_TRUE(on("plant/one/A").empty());
}

TEST_F(DatagramRouterTest, AnUnknownKeyIsCountedAndTouchesNoExchange) {
    add(plan("one", 1));
    route(datagram(7, 1, 11));
    EXPECT_EQ(dropped(DropReason::unknown_exchange), 1u);
    EXPECT_EQ(dropped_in_all(), 1u);
    EXPECT_EQ(consumers_[0]->exchange().counters().received, 0u);
}

TEST_F(DatagramRouterTest, ADatagramFromAnotherThanTheExchangesSourceIsRefusedAndCountedTwice) {
    add(plan("guarded", 1, plc));
    route(datagram(1, 1, 66), intruder);
    EXPECT_EQ(dropped(DropReason::wrong_source), 1u);
    EXPECT_EQ(consumers_[0]->wrong_source(), 1u);  // the exchange's own count, for its metrics
    EXPECT_EQ(consumers_[0]->exchange().counters().received, 0u);
    EXPECT_TRUE(on("plant/guarded/A").empty());
    // The real source still gets through, and the spoofed request id 1 did not consume its own.
    route(datagram(1, 1, 11), plc);
    EXPECT_EQ(router_.counters().accepted, 1u);
    ASSERT_EQ(on("plant/guarded/A").size(), 1u);
    EXPECT_NE(on("plant/guarded/A")[0].find("\"value\":11"), std::string::npos);
}

TEST_F(DatagramRouterTest, AnExchangesOwnRefusalIsCountedUnderItsReason) {
    add(plan("one", 1));
    route(datagram(1, 1, 11, /*length=*/8));  // configured length is 4
    EXPECT_EQ(dropped(DropReason::length_mismatch), 1u);
    EXPECT_EQ(router_.counters().accepted, 0u);
    EXPECT_EQ(consumers_[0]->exchange().counters().length_mismatches, 1u);
}

TEST_F(DatagramRouterTest, AfterAReloadOnlyTheNewConsumersAreRouted) {
    add(plan("old", 1));
    route(datagram(1, 1, 11));
    consumers_.clear();
    router_.set_consumers(consumers_);
    add(plan("new", 2));
    route(datagram(1, 2, 12));
    route(datagram(2, 1, 21));
    EXPECT_EQ(dropped(DropReason::unknown_exchange), 1u);
    EXPECT_EQ(router_.counters().accepted, 2u);
    EXPECT_EQ(on("plant/new/A").size(), 1u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
