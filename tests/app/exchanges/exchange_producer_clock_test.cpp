// ExchangeProducer reads the time through its scheduler's clock: when its configuration took
// effect, and the throttled log of its failed saves (the first logged, the next summarised once
// the interval has passed on that clock). Saves fail for real, as in exchange_producer_test.cpp:
// the state directory is replaced by a regular file. The loop never runs.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "eip2mqtt/app/exchanges/exchange_producer.hpp"
#include "tests/app/support/json_tree_recorder.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/log_capture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

class ExchangeProducerClockTest : public ::testing::Test {
protected:
    ExchangeProducerClockTest() {
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        producer_ = std::make_unique<ExchangeProducer>(
            test::test_produced_plan(), adapters::udp::Endpoint{0x7F000001, 9}, scheduler_,
            persister_, uns_.northbound(), totals_);
        persister_.flush();  // the initial image is saved
    }
    ~ExchangeProducerClockTest() override {
        producer_.reset();
        std::error_code ignored;
        fs::remove(dir_, ignored);
        fs::remove_all(dir_, ignored);
    }
    /// The next save fails: a tick arms the retry, the tick a second later saves.
    void fail_a_save() {
        producer_->on_tick(clock_.monotonic());
        persister_.flush();
        clock_.advance(1s);
        producer_->on_tick(clock_.monotonic());
        persister_.flush();
    }

    fs::path dir_ =
        fs::temp_directory_path() / ("eip2mqtt_producer_clock_" + std::to_string(::getpid()));
    boost::asio::io_context loop_;
    test::FakeClock clock_;
    adapters::state::ImageStore store_{dir_.string()};
    adapters::udp::Sender sender_{loop_.get_executor(), {}};
    ProducerScheduler scheduler_{loop_.get_executor(), sender_, clock_};
    adapters::state::ImagePersister persister_{store_, loop_.get_executor()};
    test::JsonTreeRecorder uns_;
    ImageSaveTotals totals_;
    std::unique_ptr<ExchangeProducer> producer_;
};

TEST_F(ExchangeProducerClockTest, ItIsConfiguredAtItsSchedulersClocksTime) {
    EXPECT_EQ(producer_->configured_at(), clock_.wall());
}

TEST_F(ExchangeProducerClockTest, FailedSavesAreSummarisedOnceTheIntervalPassedOnTheClock) {
    test::LogCapture log;
    fs::remove_all(dir_);
    std::ofstream(dir_.string()) << "not a directory";
    producer_->stage({{0, core::plan::Value{std::int64_t{7}}}}, {"reply/a", "a"},
                     clock_.monotonic());
    const auto wall = clock_.wall();
    producer_->produce(wall);
    producer_->on_sent(true, wall);
    persister_.flush();  // the first failure: logged
    auto lines = log.lines();
    ASSERT_FALSE(lines.empty());
    EXPECT_NE(lines.back().find("exchange sp: cannot save its image"), std::string::npos)
        << lines.back();
    fail_a_save();  // a second later, within the interval: counted, not logged
    EXPECT_EQ(producer_->counters().save_failures, 2u);
    EXPECT_TRUE(log.lines().empty());
    clock_.advance(59s);
    fail_a_save();  // 61 s after the first: the summary is due
    EXPECT_EQ(producer_->counters().save_failures, 3u);
    lines = log.lines();
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_NE(lines[0].find("exchange sp: 2 image saves failed in the last 60 s"),
              std::string::npos)
        << lines[0];
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
