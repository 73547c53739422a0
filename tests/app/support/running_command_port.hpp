#pragma once
// A command port (UDP 7937) made from a configuration over exchanges with no exchange, recording
// fakes for the writes and the northbound and a fake clock, its loop running on a thread of its
// own once started. The port is touched on that loop only: on_loop() runs work there.

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <future>
#include <memory>
#include <thread>
#include <vector>

#include "eip2mqtt/app/command_port/command_port.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/fakes/recording_write_handler.hpp"

namespace eip2mqtt::test {

/// A configuration whose command port is enabled on 127.0.0.1:`port` for the sources in `allow`.
inline core::config::Config commands_config(std::uint16_t port, const char* allow) {
    core::config::Config config;
    config.eip.bind = "127.0.0.1";
    config.eip.commands.enabled = true;
    config.eip.commands.port = port;
    config.eip.commands.allow = std::vector<core::net::Subnet>{*core::net::parse_subnet(allow)};
    return config;
}

class RunningCommandPort {
public:
    RunningCommandPort() = default;
    RunningCommandPort(const RunningCommandPort&) = delete;
    RunningCommandPort& operator=(const RunningCommandPort&) = delete;

    /// Stops the port on its loop (when one was started), then ends the loop's thread.
    ~RunningCommandPort() {
        if (port_) on_loop([this] { port_->stop(); });
        guard_.reset();
        if (thread_.joinable()) thread_.join();
    }

    /// The port `config` makes (null when its commands are not enabled), not started.
    std::unique_ptr<app::Module> make(const core::config::Config& config) {
        return app::command_port::make_command_port(config, loop_.get_executor(), exchanges_,
                                                    writes_, clock_);
    }

    /// Makes the port, starts it and runs its loop on the thread.
    void start(const core::config::Config& config) {
        port_ = make(config);
        ASSERT_NE(port_, nullptr);
        port_->start(clock_.monotonic());
        thread_ = std::thread([this] { loop_.run(); });
    }

    /// The running port: to be used inside on_loop() only.
    app::Module& port() { return *port_; }

    /// Runs `work` on the loop and waits for it.
    void on_loop(std::function<void()> work) {
        using namespace std::chrono_literals;
        std::promise<void> done;
        boost::asio::post(loop_, [&] {
            work();
            done.set_value();
        });
        ASSERT_EQ(done.get_future().wait_for(10s), std::future_status::ready);
    }

    /// The port's command counters, read on the loop.
    core::command::CommandCounters counters() {
        core::command::CommandCounters copy;
        on_loop([&] {
            app::DatagramCounters datagrams;
            app::WriteCounters writes;
            adapters::mqtt::ClientStats mqtt;
            app::MetricsSources sources{datagrams, writes, mqtt};
            port_->add_metrics(sources);
            copy = *sources.commands;
        });
        return copy;
    }

private:
    boost::asio::io_context loop_;
    boost::asio::executor_work_guard<boost::asio::io_context::executor_type> guard_{
        loop_.get_executor()};
    RecordingNorthbound northbound_;
    app::ImageSaveTotals totals_;
    app::Exchanges exchanges_{loop_.get_executor(), app::ExchangesOptions{}, northbound_, totals_};
    RecordingWriteHandler writes_;
    FakeClock clock_;
    std::unique_ptr<app::Module> port_;
    std::thread thread_;
};

}  // namespace eip2mqtt::test
