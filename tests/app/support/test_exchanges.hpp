#pragma once
// Running exchanges for unit tests of what reads them (the status documents, the status
// module): a state directory of the test's own, removed with them, a recording northbound and
// the test's clock. The loop is the test's; it need not run.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <filesystem>
#include <memory>
#include <string>

#include "eip2mqtt/app/exchanges/exchanges.hpp"
#include "tests/support/fakes/recording_northbound.hpp"

namespace eip2mqtt::test {

class TestExchanges {
public:
    /// `loop` and `clock` must outlive them; `prefix` names the state directory, with the
    /// running test's name and the process id.
    TestExchanges(boost::asio::io_context& loop, const core::Clock& clock,
                  const std::string& prefix)
        : dir_(std::filesystem::temp_directory_path() /
               (prefix + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                "_" + std::to_string(::getpid()))) {
        std::filesystem::create_directories(dir_);
        app::ExchangesOptions options;
        options.sender.bind = "127.0.0.1";
        options.state_dir = dir_.string();
        exchanges_ = std::make_unique<app::Exchanges>(loop.get_executor(), std::move(options),
                                                      northbound_, totals_, clock);
    }
    ~TestExchanges() {
        exchanges_.reset();
        std::filesystem::remove_all(dir_);
    }
    TestExchanges(const TestExchanges&) = delete;
    TestExchanges& operator=(const TestExchanges&) = delete;

    app::Exchanges& operator*() { return *exchanges_; }
    app::Exchanges* operator->() { return exchanges_.get(); }

private:
    std::filesystem::path dir_;
    RecordingNorthbound northbound_;
    app::ImageSaveTotals totals_;
    std::unique_ptr<app::Exchanges> exchanges_;
};

}  // namespace eip2mqtt::test
