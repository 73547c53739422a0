// The status module on a real listener: each request is handed to the loop and answered from
// it, a loop that does not turn gets 503 rather than a hung request, a reload shows in the
// facts, and a stopped module serves nothing more.

#include "eip2mqtt/app/status/status_module.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <filesystem>
#include <future>
#include <nlohmann/json.hpp>

#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/http_get.hpp"

namespace eip2mqtt::app::status {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using json = nlohmann::json;

class StatusModuleTest : public ::testing::Test {
protected:
    StatusModuleTest() : endpoint_("127.0.0.1:0") {
        module_ =
            make_status_module(config_, loop_.get_executor(), clock_, south_, &endpoint_, [this] {
                return MetricsSources{south_.exchanges().datagram_counters(), writes_, mqtt_};
            });
        module_->start(clock_.monotonic());
    }
    ~StatusModuleTest() override {
        module_.reset();
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }
    /// A gateway `gw` of `/etc/a.yaml`, its state in `dir`, its data port any free one.
    static core::config::Config config_in(const std::filesystem::path& dir) {
        core::config::Config config;
        config.gateway.id = "gw";
        config.file = "/etc/a.yaml";
        config.gateway.state_dir = dir.string();
        config.eip.bind = "127.0.0.1";
        config.eip.port = 0;
        return config;
    }
    /// GET `path` on a thread of its own while the loop runs here until it is answered.
    std::pair<std::string, std::string> get_with_loop(const std::string& path) {
        auto response = std::async(std::launch::async,
                                   [this, path] { return test::http_get(endpoint_.port(), path); });
        while (response.wait_for(0s) != std::future_status::ready) {
            loop_.run_one_for(10ms);
        }
        return test::status_and_body(response.get());
    }

    boost::asio::io_context loop_;
    /// The loop has work while nothing is posted: run_one_for waits rather than stop it.
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work_{
        loop_.get_executor()};
    test::FakeClock clock_;
    std::filesystem::path dir_ =
        std::filesystem::temp_directory_path() /
        ("eip2mqtt_status_module_" +
         std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
         std::to_string(::getpid()));
    core::config::Config config_ = config_in(dir_);
    ExchangesModule south_{config_, loop_.get_executor(), clock_, {}};
    core::write::WriteCounters writes_;
    adapters::mqtt::ClientStats mqtt_;
    adapters::metrics::PrometheusEndpoint endpoint_;
    std::unique_ptr<Module> module_;
};

TEST_F(StatusModuleTest, TheLoopAnswersEachRequestAndAReloadShows) {
    auto [code, body] = get_with_loop("/api/status");
    ASSERT_EQ(code, "200") << body;
    auto doc = json::parse(body);
    EXPECT_EQ(doc["gateway"]["id"], "gw");
    EXPECT_EQ(doc["gateway"]["config"]["reloads"], 0);

    clock_.advance(10s);
    auto next = config_;
    next.file = "/etc/b.yaml";
    module_->apply(next);
    std::tie(code, body) = get_with_loop("/api/status");
    doc = json::parse(body);
    EXPECT_EQ(doc["gateway"]["config"]["file"], "/etc/b.yaml");
    EXPECT_EQ(doc["gateway"]["config"]["reloads"], 1);
    EXPECT_EQ(doc["gateway"]["config"]["loaded_at"].get<std::int64_t>() -
                  doc["gateway"]["started_at"].get<std::int64_t>(),
              10000);
    EXPECT_EQ(get_with_loop("/api/exchanges/none").first, "404");
}

TEST_F(StatusModuleTest, ALoopThatDoesNotTurnIsAnswered503AndAStoppedModuleNothing) {
    // Nobody runs the loop: the request waits its bound, then says why.
    const auto [code, body] =
        test::status_and_body(test::http_get(endpoint_.port(), "/api/status"));
    EXPECT_EQ(code, "503");
    EXPECT_NE(body.find("did not answer"), std::string::npos) << body;
    module_->stop();
    EXPECT_EQ(get_with_loop("/api/status").first, "404");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::status
