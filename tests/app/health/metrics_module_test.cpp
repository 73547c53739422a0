// The metrics module: the metrics go to its northbound every mqtt.metrics_interval (the loop's
// timer, waited on by events, never by sleeping), a reload's new interval replaces the wait
// under way, and with metrics.listen the Prometheus endpoint takes new figures on the ticks that
// scan (refresh_scan) and on no other.

#include "eip2mqtt/app/health/metrics_module.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <string>

#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/http_get.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

class MetricsModuleTest : public ::testing::Test {
protected:
    MetricsModuleTest()
        : dir_(fs::temp_directory_path() /
               ("eip2mqtt_metrics_module_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()))) {
        ExchangesOptions options;
        options.state_dir = dir_.string();
        exchanges_ = std::make_unique<Exchanges>(loop_.get_executor(), std::move(options),
                                                 exchanges_north_, totals_);
    }
    ~MetricsModuleTest() override {
        module_.reset();
        exchanges_.reset();
        fs::remove_all(dir_);
    }

    void make(std::chrono::seconds interval, std::string listen = "") {
        config_.mqtt.metrics_interval = interval;
        config_.metrics.listen = std::move(listen);
        module_ = std::make_unique<MetricsModule>(
            config_, loop_.get_executor(), clock_, *exchanges_, north_,
            [this] {
                ++asked_;
                return MetricsSources{datagrams_, writes_, mqtt_};
            },
            [this](const MetricsSources&) { ++published_; });
    }
    /// Runs the loop until `published` publications were made; false after 30 s.
    bool run_until_published(int published) {
        const auto deadline = std::chrono::steady_clock::now() + 30s;
        while (published_ < published && std::chrono::steady_clock::now() < deadline) {
            loop_.run_one_for(100ms);
        }
        return published_ >= published;
    }
    std::size_t metrics_events() const {
        return static_cast<std::size_t>(
            std::count(north_.events.begin(), north_.events.end(), "metrics"));
    }
    TickTimes tick(bool refresh_scan) const {
        return {clock_.monotonic(), clock_.wall(), refresh_scan};
    }

    fs::path dir_;
    boost::asio::io_context loop_;
    test::FakeClock clock_;
    test::RecordingNorthbound exchanges_north_;
    ImageSaveTotals totals_;
    std::unique_ptr<Exchanges> exchanges_;
    test::RecordingNorthbound north_;
    core::config::Config config_;
    DatagramCounters datagrams_;
    WriteCounters writes_;
    adapters::mqtt::ClientStats mqtt_;
    int asked_ = 0;
    int published_ = 0;
    std::unique_ptr<MetricsModule> module_;
};

TEST_F(MetricsModuleTest, PublishesTheMetricsToItsNorthboundEveryInterval) {
    make(1s);
    module_->start(clock_.monotonic());
    EXPECT_EQ(metrics_events(), 0u);  // the first interval has not passed
    ASSERT_TRUE(run_until_published(2));
    EXPECT_EQ(metrics_events(), 2u);
    EXPECT_EQ(asked_, 2);
    module_->stop();
}

TEST_F(MetricsModuleTest, AReloadWithANewIntervalReplacesTheWaitUnderWay) {
    make(std::chrono::hours(1));
    module_->start(clock_.monotonic());
    auto next = config_;
    next.mqtt.metrics_interval = 1s;
    module_->apply(next);
    // Within the bound only if the hour's wait was replaced by the second's.
    ASSERT_TRUE(run_until_published(2));
    EXPECT_EQ(metrics_events(), 2u);
    module_->stop();
}

TEST_F(MetricsModuleTest, StopCancelsThePublication) {
    make(1s);
    module_->start(clock_.monotonic());
    module_->stop();
    loop_.run_for(10s);  // returns at once: nothing is left to wait for
    EXPECT_EQ(published_, 0);
    EXPECT_EQ(metrics_events(), 0u);
}

TEST_F(MetricsModuleTest, ThePrometheusEndpointIsUpdatedOnTicksThatScanOnly) {
    const auto port = test::free_tcp_port();
    make(std::chrono::hours(1), "127.0.0.1:" + std::to_string(port));
    module_->start(clock_.monotonic());
    mqtt_.published = 4242;
    module_->tick(tick(false));
    EXPECT_EQ(asked_, 0);
    const auto before = test::http_get(port, "/metrics");
    ASSERT_FALSE(before.empty()) << "the endpoint did not answer on port " << port;
    EXPECT_EQ(before.find("eip2mqtt_mqtt_published_total 4242"), std::string::npos);

    module_->tick(tick(true));
    EXPECT_EQ(asked_, 1);
    EXPECT_NE(test::http_get(port, "/metrics").find("eip2mqtt_mqtt_published_total 4242"),
              std::string::npos);
    module_->stop();
}

TEST_F(MetricsModuleTest, WithoutAnEndpointATickAsksForNothing) {
    make(std::chrono::hours(1));
    module_->start(clock_.monotonic());
    module_->tick(tick(true));
    EXPECT_EQ(asked_, 0);
    module_->stop();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
