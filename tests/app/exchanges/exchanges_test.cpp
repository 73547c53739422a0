// Exchanges: what apply() keeps, starts and stops, by name; what the northbound learns; writes
// staged by a producer's handle, a stale handle refused, a stopped producer's queued writes
// answered. Consumed exchanges open no socket; a produced one opens the sending socket on
// 127.0.0.1. The loop never runs: nothing depends on time.

#include "eip2mqtt/app/exchanges/exchanges.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/app/support/test_plan.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/recording_northbound.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using core::plan::Direction;
using core::plan::TagType;
using Names = std::vector<std::string>;

core::plan::ExchangePlan plan(std::string name, Direction direction, std::uint32_t exchange_id,
                              core::plan::TagSpec tag) {
    return test::test_exchange(std::move(name), direction, exchange_id, std::move(tag));
}

core::plan::ExchangePlan consumed(std::string name, std::uint32_t exchange_id,
                                  std::string tag = "A") {
    return plan(std::move(name), Direction::consume, exchange_id,
                test::test_tag(std::move(tag), 0, TagType::dint));
}

core::plan::ExchangePlan produced(std::string name, std::uint32_t exchange_id) {
    return plan(std::move(name), Direction::produce, exchange_id,
                test::test_tag("VALUE", 0, TagType::dint, true));
}

template <class... Plans>
std::vector<core::plan::ExchangePlan> plans(Plans... each) {
    std::vector<core::plan::ExchangePlan> out;
    (out.push_back(std::move(each)), ...);
    return out;
}

class ExchangesTest : public ::testing::Test {
protected:
    ExchangesTest() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() / ("eip2mqtt_exchanges_" + std::string(info->name()) +
                                            "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        ExchangesOptions options;
        options.sender.bind = "127.0.0.1";
        options.state_dir = dir_.string();
        exchanges_ = std::make_unique<Exchanges>(loop_.get_executor(), std::move(options),
                                                 northbound_, totals_);
    }
    ~ExchangesTest() override {
        exchanges_.reset();
        fs::remove_all(dir_);
    }
    ApplyReport apply(std::vector<core::plan::ExchangePlan> next) {
        return exchanges_->apply(std::move(next), now_, wall_);
    }
    std::optional<core::write::WriteRejection> stage(ProducerHandle producer, std::int64_t value) {
        WriteReply reply{"reply/topic", "", &northbound_, WriteOrigin::mqtt};
        return exchanges_->stage(ExchangeWrite{producer, {{0, core::plan::Value{value}}}}, reply,
                                 now_);
    }

    fs::path dir_;
    boost::asio::io_context loop_;
    test::RecordingNorthbound northbound_;
    ImageSaveTotals totals_;
    core::MonoTime now_ = core::MonoTime{} + 1h;
    core::WallTime wall_ = core::WallTime{} + 1h;
    std::unique_ptr<Exchanges> exchanges_;
};

TEST_F(ExchangesTest, TheFirstApplyStartsEveryExchangeAndTellsTheNorthbound) {
    const auto report = apply(plans(consumed("a", 1), consumed("b", 2)));
    EXPECT_EQ(report.started, (Names{"a", "b"}));
    EXPECT_TRUE(report.kept.empty());
    EXPECT_TRUE(report.stopped.empty());
    EXPECT_EQ(northbound_.events, Names{"exchanges"});
    EXPECT_EQ(northbound_.consumed, 2u);
    EXPECT_EQ(exchanges_->consumers().size(), 2u);
    EXPECT_TRUE(exchanges_->producers().empty());
}

TEST_F(ExchangesTest, AReloadKeepsTheUnchangedStartsTheNewAndStopsTheRemovedByName) {
    apply(plans(consumed("a", 1), consumed("b", 2), consumed("c", 3)));
    const auto* kept = &exchanges_->consumers()[0]->plan();
    exchanges_->start(now_);
    const auto report = apply(plans(consumed("a", 1), consumed("c", 3, "B"), consumed("d", 4)));
    EXPECT_EQ(report.kept, Names{"a"});
    EXPECT_EQ(report.started, (Names{"c", "d"}));  // c changed: restarted
    EXPECT_EQ(report.stopped, (Names{"b", "c"}));
    // b's topics and c's old tag topic are used by no running exchange: cleared.
    EXPECT_EQ(northbound_.retired,
              (Names{"acme/b/A", "acme/b/_meta", "acme/b/_status", "acme/c/A"}));
    EXPECT_EQ(report.cleared_topics, 4u);
    EXPECT_EQ(&exchanges_->consumers()[0]->plan(), kept);
}

TEST_F(ExchangesTest, DatagramsReachTheConsumersOfTheLastApply) {
    apply(plans(consumed("a", 1)));
    apply(plans(consumed("b", 2)));
    const auto to_a = test::DatagramBuilder("10.0.0.1", 1, 4).request_id(1).build();
    const auto to_b = test::DatagramBuilder("10.0.0.1", 2, 4).request_id(1).build();
    exchanges_->route(to_a, {0x0A000001, 18246}, false, now_);
    exchanges_->route(to_b, {0x0A000001, 18246}, false, now_);
    EXPECT_EQ(exchanges_->datagram_counters().datagrams, 2u);
    EXPECT_EQ(exchanges_->datagram_counters().accepted, 1u);
    EXPECT_EQ(exchanges_->datagram_counters().dropped_for(core::wire::DropReason::unknown_exchange),
              1u);
}

TEST_F(ExchangesTest, AWriteIsStagedByItsProducersHandle) {
    apply(plans(consumed("in", 1), produced("out", 2)));
    ASSERT_EQ(exchanges_->producers().size(), 1u);
    const auto* handle = &exchanges_->producers()[0]->plan();
    EXPECT_EQ(northbound_.produced, 1u);
    EXPECT_FALSE(stage(handle, 7).has_value());
    EXPECT_EQ(exchanges_->producers()[0]->counters().writes_applied, 0u);  // applied when sent
    // A consumed exchange's plan names no producer.
    const auto refused = stage(&exchanges_->consumers()[0]->plan(), 7);
    ASSERT_TRUE(refused.has_value());
}

TEST_F(ExchangesTest, AReloadAnswersTheQueuedWritesOfAStoppedProducer) {
    apply(plans(produced("out", 2)));
    exchanges_->start(now_);
    ASSERT_FALSE(stage(&exchanges_->producers()[0]->plan(), 7).has_value());
    const auto report = apply(plans(produced("other", 3)));
    EXPECT_EQ(report.stopped, Names{"out"});
    EXPECT_EQ(report.started, Names{"other"});
    EXPECT_EQ(report.cancelled_writes, 1u);
    ASSERT_EQ(northbound_.results.size(), 1u);
    EXPECT_EQ(northbound_.results[0].error, "reloaded");
    EXPECT_FALSE(stage(&exchanges_->producers()[0]->plan(), 8).has_value());
}

TEST_F(ExchangesTest, AHandleNoRunningProducerHasIsRefused) {
    apply(plans(produced("out", 2)));
    const auto elsewhere = produced("out", 2);  // equal, but not the running producer's plan
    const auto refused = stage(&elsewhere, 7);
    ASSERT_TRUE(refused.has_value());
    EXPECT_EQ(refused->error, core::write::WriteError::unknown_tag);
    EXPECT_TRUE(northbound_.results.empty());  // the dispatcher answers refusals, not Exchanges
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
