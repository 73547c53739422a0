#include "eip2mqtt/app/reload/reload_sequence.hpp"

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <chrono>
#include <string>
#include <vector>

#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::app::reload {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// A gateway as a reload sees it: what it is asked, in order, and a change of `pending`
/// publications that leave its queue as they are published.
class FakeTarget final : public ReloadTarget {
public:
    explicit FakeTarget(boost::asio::io_context& loop) : loop_(loop) {}

    const std::string& file() const override { return file_; }
    void reloading() override { calls.push_back("reloading"); }
    bool apply(ParseResult parsed, std::vector<std::string>& outcome) override {
        calls.push_back(parsed ? "apply " + parsed->config.file : "refused");
        if (!parsed) return false;
        outcome.push_back("applied");
        return true;
    }
    bool changes_pending() const override { return pending > 0; }
    void publish_changes(std::size_t units) override {
        const auto n = std::min(units, pending);
        calls.push_back("slice " + std::to_string(n));
        pending -= n;
        queued += n;
    }
    core::config::PublishQueueRoom queue_room() const override { return {queued, capacity, true}; }
    void ready() override {
        calls.push_back("ready");
        loop_.stop();
    }
    bool stopping() const override { return false; }

    std::vector<std::string> calls;
    std::size_t pending = 0;
    std::size_t queued = 0;
    std::size_t capacity = 100000;

private:
    boost::asio::io_context& loop_;
    std::string file_ = "gateway.yaml";
};

ParseResult parsed_file(const std::string& path, std::stop_token) {
    ParsedConfig parsed;
    parsed.config.file = path;
    return parsed;
}

ParseResult broken_file(const std::string&, std::stop_token) {
    return core::fail(core::config::Diagnostics{});
}

TEST(ReloadSequence, AppliesTheParsedFileThenPublishesItsChangesInSlicesThenSaysReady) {
    boost::asio::io_context loop;
    // The parse's result comes from the worker's thread: the loop waits for it.
    const auto work = boost::asio::make_work_guard(loop);
    FakeTarget target(loop);
    target.pending = 2500;
    test::FakeClock clock;
    ReloadSequence sequence(loop.get_executor(), target, clock, parsed_file);
    sequence.request();
    loop.run_for(10s);
    EXPECT_EQ(target.calls,
              (std::vector<std::string>{"reloading", "apply gateway.yaml", "slice 1000",
                                        "slice 1000", "slice 500", "ready"}));
}

TEST(ReloadSequence, ARefusedFileIsSaidReadyWithNothingPublished) {
    boost::asio::io_context loop;
    // The parse's result comes from the worker's thread: the loop waits for it.
    const auto work = boost::asio::make_work_guard(loop);
    FakeTarget target(loop);
    test::FakeClock clock;
    ReloadSequence sequence(loop.get_executor(), target, clock, broken_file);
    sequence.request();
    loop.run_for(10s);
    EXPECT_EQ(target.calls, (std::vector<std::string>{"reloading", "refused", "ready"}));
}

TEST(ReloadSequence, ASliceWaitsWhileThePublishQueueIsHalfFullAndGoesOnOnceItDrained) {
    boost::asio::io_context loop;
    // The parse's result comes from the worker's thread: the loop waits for it.
    const auto work = boost::asio::make_work_guard(loop);
    FakeTarget target(loop);
    target.pending = 1500;
    target.capacity = 2000;
    test::FakeClock clock;
    ReloadSequence sequence(loop.get_executor(), target, clock, parsed_file);
    sequence.request();
    // Run until the first slices filled half the queue and the sequence waits on it.
    while (target.queued < 1000 && loop.run_one_for(10s) > 0) {
    }
    ASSERT_GE(target.queued, 1000u);
    const auto slices_before = target.calls.size();
    loop.run_for(50ms);  // nothing drains: no slice goes
    EXPECT_EQ(target.calls.size(), slices_before);
    target.queued = 0;  // the broker took them
    loop.restart();
    loop.run_for(10s);
    EXPECT_EQ(target.pending, 0u);
    EXPECT_EQ(target.calls.back(), "ready");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::reload
