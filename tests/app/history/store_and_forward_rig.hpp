#pragma once
// What the store-and-forward tests share: a real journal file in a directory of the test's own,
// a recording sink and a connection the test switches (store_and_forward_test.cpp,
// store_and_forward_sinks_test.cpp).

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tests/app/support/test_plan.hpp"
#include "tests/support/fakes/recording_history_sink.hpp"

namespace eip2mqtt::app::history::test_rig {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using core::plan::Direction;
using core::plan::TagType;
using core::quality::Quality;
using test::RecordingHistorySink;

class StoreAndForwardTest : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = fs::temp_directory_path() /
               ("eip2mqtt_saf_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        open();
    }
    void TearDown() override {
        saf_.reset();
        fs::remove_all(dir_);
    }

    void open(std::uint32_t replay_rate = 100, const core::Clock* clock = nullptr) {
        saf_.reset();
        std::string set_aside;
        auto journal = adapters::history::Journal::open(
            {(dir_ / "history.sqlite").string(), 256ull << 20}, set_aside);
        StoreAndForwardOptions options{replay_rate, 1000ms};
        if (clock) options.clock = clock;
        saf_ = std::make_unique<StoreAndForward>(
            std::move(journal), std::move(options),
            LinkProbe{[this] { return connected_; }, [this] { return backlog(); }}, sink_);
        saf_->exchanges_changed({{&plant_}, {&produced_}}, {});
    }

    /// One datagram's change of the counter (tag 1), at `timestamp`.
    void counter(std::int64_t value, std::int64_t timestamp = 1000, Quality quality = Quality::good,
                 bool all_tags = false, const core::plan::ExchangePlan* plan = nullptr) {
        const std::vector<TagSample> samples{{1, core::plan::Value{value}}};
        saf_->tag_samples({plan ? *plan : plant_, quality, timestamp, all_tags, samples});
    }

    /// Ticks every 10 ms for `duration`; the journal's writer is waited for after each tick,
    /// so that what a tick hands over is in the journal at the next.
    void run_for(std::chrono::milliseconds duration) {
        for (auto t = 0ms; t < duration; t += 10ms) {
            now_ += 10ms;
            saf_->on_tick(now_);
            saf_->flush();
        }
    }
    void reconnect() {
        connected_ = true;
        saf_->on_connected(now_);
    }
    void acknowledge_all() {
        for (const auto& r : sink_.replayed) {
            if (acknowledged_.insert(r.token).second) saf_->on_acknowledged(r.token);
        }
    }
    /// By default the client holds what it was given until it is acknowledged.
    std::uint64_t backlog() const {
        return backlog_ ? *backlog_ : sink_.replayed.size() - acknowledged_.size();
    }
    std::vector<std::int64_t> replayed_values(std::size_t from = 0) const {
        std::vector<std::int64_t> values;
        for (std::size_t i = from; i < sink_.replayed.size(); ++i) {
            values.push_back(sink_.replayed[i].samples.at(0).second);
        }
        return values;
    }
    std::uint64_t entries() { return saf_->stats().journal.entries; }

    core::plan::ExchangePlan plant_ = test::test_plan(
        "plant", Direction::consume, 8,
        {test::test_tag("state", 0, TagType::dint), test::test_tag("counter", 4, TagType::dint)});
    core::plan::ExchangePlan produced_ = test::test_plan("setpoints", Direction::produce, 4,
                                                         {test::test_tag("sp", 0, TagType::dint)});
    fs::path dir_;
    bool connected_ = false;
    std::optional<std::uint64_t> backlog_;
    std::set<std::uint64_t> acknowledged_;
    core::MonoTime now_ = std::chrono::steady_clock::now();
    RecordingHistorySink sink_;
    std::unique_ptr<StoreAndForward> saf_;
};

}  // namespace eip2mqtt::app::history::test_rig
