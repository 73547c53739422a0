// Exchanges read the time through the clock they are given: each consumer and producer says
// when its configuration took effect (the command port's config_time) from that clock, and an
// exchange a reload keeps keeps its time. The loop never runs.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_northbound.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using core::plan::Direction;
using core::plan::TagType;

core::plan::ExchangePlan plan(std::string name, Direction direction, std::uint32_t exchange_id) {
    return test::test_exchange(
        std::move(name), direction, exchange_id,
        test::test_tag("VALUE", 0, TagType::dint, direction == Direction::produce));
}

class ExchangesClockTest : public ::testing::Test {
protected:
    ExchangesClockTest() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ =
            fs::temp_directory_path() / ("eip2mqtt_exchanges_clock_" + std::string(info->name()) +
                                         "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        ExchangesOptions options;
        options.sender.bind = "127.0.0.1";
        options.state_dir = dir_.string();
        exchanges_ = std::make_unique<Exchanges>(loop_.get_executor(), std::move(options),
                                                 northbound_, totals_, clock_);
    }
    ~ExchangesClockTest() override {
        exchanges_.reset();
        fs::remove_all(dir_);
    }
    void apply(std::vector<core::plan::ExchangePlan> plans) {
        exchanges_->apply(std::move(plans), clock_.monotonic(), clock_.wall());
    }

    fs::path dir_;
    boost::asio::io_context loop_;
    test::RecordingNorthbound northbound_;
    ImageSaveTotals totals_;
    test::FakeClock clock_;
    std::unique_ptr<Exchanges> exchanges_;
};

TEST_F(ExchangesClockTest, EachExchangeIsConfiguredAtTheTimeOfItsClock) {
    const auto first = clock_.wall();
    std::vector<core::plan::ExchangePlan> plans;
    plans.push_back(plan("in", Direction::consume, 1));
    plans.push_back(plan("out", Direction::produce, 2));
    apply(std::move(plans));
    ASSERT_EQ(exchanges_->consumers().size(), 1u);
    ASSERT_EQ(exchanges_->producers().size(), 1u);
    EXPECT_EQ(exchanges_->consumers()[0]->configured_at(), first);
    EXPECT_EQ(exchanges_->producers()[0]->configured_at(), first);

    // A reload a day later: the kept exchanges keep their time, the new ones take the clock's.
    clock_.advance(24h);
    plans.clear();
    plans.push_back(plan("in", Direction::consume, 1));
    plans.push_back(plan("in2", Direction::consume, 3));
    plans.push_back(plan("out", Direction::produce, 2));
    plans.push_back(plan("out2", Direction::produce, 4));
    apply(std::move(plans));
    ASSERT_EQ(exchanges_->consumers().size(), 2u);
    ASSERT_EQ(exchanges_->producers().size(), 2u);
    EXPECT_EQ(exchanges_->consumers()[0]->configured_at(), first);
    EXPECT_EQ(exchanges_->consumers()[1]->configured_at(), first + 24h);
    EXPECT_EQ(exchanges_->producers()[0]->configured_at(), first);
    EXPECT_EQ(exchanges_->producers()[1]->configured_at(), first + 24h);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
