#pragma once
// What the tests of the northbound modules share (json_tree_module_test.cpp,
// store_and_forward_module_test.cpp, northbounds_test.cpp, sparkplug_module_test.cpp): a
// configuration of the test's own (one consumed exchange "a" on loopback, eip.port 0, a state
// directory of its own), the exchanges module, a role, and the parts a northbound module is made
// of. The loop runs on the test's thread, until an awaited event or a bound.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/exchanges/exchanges_module.hpp"
#include "eip2mqtt/app/northbound/northbounds.hpp"
#include "eip2mqtt/app/redundancy/role.hpp"
#include "eip2mqtt/app/reload/reload_sequence.hpp"
#include "tests/support/datagram_builder.hpp"

namespace eip2mqtt::test {

class NorthboundRig : public ::testing::Test {
protected:
    NorthboundRig()
        : dir_(std::filesystem::temp_directory_path() /
               ("eip2mqtt_northbound_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()))) {
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_ / "state");
    }
    ~NorthboundRig() override { std::filesystem::remove_all(dir_); }

    /// The configuration of the broker at `url`, with `extra` YAML appended to `mqtt:`
    /// (indented by two) and `sections` after it (whole top-level sections).
    core::config::Config config(const std::string& url, const std::string& extra = "",
                                const std::string& sections = "") {
        auto loaded = adapters::yaml::load_config_text(
            "gateway:\n  id: gw\n  state_dir: " + (dir_ / "state").string() +
                "\nmqtt:\n  url: " + url + "\n  base_topic: acme\n" + extra + sections +
                "eip:\n  bind: 127.0.0.1\n  port: 0\nexchanges:\n"
                "  - { name: a, direction: consume, producer_id: 10.0.0.1, exchange_id: 1,\n"
                "      length: 4, tags: [ { name: T, address: \"0.0\", type: dint } ] }\n",
            (dir_ / "gateway.yaml").string());
        EXPECT_TRUE(loaded) << "the test's configuration does not load";
        return std::move(loaded).value();
    }

    /// The role (a single unit's unless given), the exchanges module running `config_`'s
    /// exchanges (`apply`: else none until apply_plans()), and the parts made of them.
    void make_parts(std::unique_ptr<app::redundancy::Role> role = nullptr, bool apply = true) {
        role_ = role ? std::move(role)
                     : app::redundancy::make_role(config_, loop_.get_executor(), clock());
        south_ = std::make_unique<app::ExchangesModule>(config_, loop_.get_executor(), clock(),
                                                        role_->exchanges_options());
        if (apply) apply_plans();
        parts_ =
            std::make_unique<app::northbound::NorthboundParts>(app::northbound::NorthboundParts{
                loop_.get_executor(), clock(), *role_, south_->writes(), south_->exchanges(),
                south_->north()});
    }

    /// Runs `config_`'s exchanges, telling the fan-out.
    void apply_plans() {
        auto copy = config_;
        south_->apply_plans(app::reload::take_plans(copy));
    }

    /// One datagram of exchange "a" carrying `value`, routed as the receiver would.
    void datagram(std::int32_t value, std::uint16_t request_id) {
        const auto bytes =
            DatagramBuilder("10.0.0.1", 1, 4)
                .request_id(request_id)
                .set("0.0", core::plan::TagType::dint, core::plan::Value{std::int64_t{value}})
                .build();
        south_->exchanges().route(bytes, {0x0A000001, 18246}, false, clock().monotonic());
    }

    /// Runs the loop until `done` holds; false after 30 s.
    bool run_until(const std::function<bool()>& done) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (!done() && std::chrono::steady_clock::now() < deadline) {
            loop_.run_one_for(std::chrono::milliseconds(50));
        }
        return done();
    }

    static const core::Clock& clock() { return adapters::clock::system_clock(); }

    std::filesystem::path dir_;
    boost::asio::io_context loop_;
    /// The loop waits for the connections' events even while nothing is pending on it.
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> work_ =
        boost::asio::make_work_guard(loop_);
    core::config::Config config_;
    std::unique_ptr<app::redundancy::Role> role_;
    std::unique_ptr<app::ExchangesModule> south_;
    std::unique_ptr<app::northbound::NorthboundParts> parts_;
};

}  // namespace eip2mqtt::test
