// The whole datagram path of consumed exchanges, router to publisher, wired as the gateway wires
// it (redundancy::Pair): once warm, a datagram that changes every tag allocates
// nothing, with or without a hot-standby pair configured. With one, the FanOut's tap keeps each
// sample in its exchange's window (PairHistory) and the leader's publications carry the tokens
// of its watermarks (JsonTree::set_sample_tokens); the standby keeps its windows without a word
// north. Counted with a replaced operator new, on this thread (tests/support/count_allocations).

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/app/exchanges/datagram_router.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "eip2mqtt/app/redundancy/pair_history.hpp"
#include "tests/app/support/json_tree_recorder.hpp"
#include "tests/support/count_allocations.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/switched_role.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using core::plan::TagType;

constexpr std::uint32_t kExchanges = 3;
constexpr int kTags = 10;
// Each exchange's period; its datagrams come in turn, one every period / kExchanges.
constexpr auto kPeriod = 9ms;
// Warm: 1.35 s of datagrams, past the arrival statistics' second and the pair's window span
// (2 x takeover, 400 ms), so that every buffer has reached its size.
constexpr int kWarm = 150;
constexpr int kMeasured = 100;

core::plan::ExchangePlan plan(std::uint32_t exchange_id) {
    core::plan::ExchangeSpec spec;
    spec.name = "e" + std::to_string(exchange_id);
    spec.direction = core::plan::Direction::consume;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = exchange_id;
    spec.length = 4 * kTags;
    spec.period = kPeriod;
    spec.topic = "turbine/" + spec.name;
    for (int i = 0; i < kTags; ++i) {
        core::plan::TagSpec tag;
        tag.name = "GENERATOR_TAG_" + std::to_string(i);
        tag.address = {static_cast<std::uint16_t>(4 * i), 0};
        tag.type = TagType::dint;
        spec.tags.push_back(tag);
    }
    return core::plan::make_exchange_plan(std::move(spec), "acme/blumenau");
}

enum class Pair { none, leader, standby };

/// Router, consumers, FanOut and JSON tree over a publisher that hands back the buffers of the
/// message before (as Client::publish does); with a pair, its window of samples as the FanOut's
/// tap and its tokens on the leader's publications.
class DatagramPath {
public:
    explicit DatagramPath(Pair pair) : pair_(pair) {
        fan_out_.add(uns_.northbound());
        if (pair_ != Pair::none) {
            role_.leading = pair_ == Pair::leader;
            fan_out_.set_role(role_);
            fan_out_.set_tap(history_);
            uns_.northbound().set_sample_tokens(
                [this](const SampleBatch& batch) { return history_.token_for(batch); });
            router_.set_followed({}, role_);  // follows while it does not lead
        }
        ExchangeSet running;
        for (std::uint32_t id = 1; id <= kExchanges; ++id) {
            consumers_.push_back(std::make_unique<ExchangeConsumer>(plan(id), fan_out_));
            running.consumed.push_back(&consumers_.back()->plan());
        }
        fan_out_.exchanges_changed(running, {});
        router_.set_consumers(consumers_);
        // Built ahead: the builder allocates, the path under test must not.
        for (int n = 1; n <= kWarm + kMeasured; ++n) {
            for (std::uint32_t id = 1; id <= kExchanges; ++id) datagrams_.push_back(build(id, n));
        }
    }

    /// The next `rounds` datagrams of each exchange, every tag changed; the leader's broker
    /// acknowledges each publication that carries a token.
    void route(int rounds) {
        for (int r = 0; r < rounds; ++r) {
            for (std::uint32_t id = 1; id <= kExchanges; ++id) {
                clock_.advance(kPeriod / kExchanges);
                router_.route(datagrams_.at(next_++), {0x0A000001, 18246}, false,
                              clock_.monotonic());
                const auto token = uns_.publisher.last.ack_token;
                if (pair_ == Pair::leader && token != 0) history_.on_acknowledged(token);
            }
        }
    }

    test::FakeClock clock_;
    test::JsonTreeRecorder uns_{{}, test::RecordingPublisher::Mode::keep_last};
    redundancy::PairHistory history_{{200ms}, uns_.northbound(), [] { return 0; }, clock_};
    DatagramRouter router_{clock_};

private:
    /// Datagram `n` of exchange `id`: request id n, stamped n periods after the fake wall
    /// clock's start, tag i = n * (i + 1).
    static std::vector<std::byte> build(std::uint32_t id, int n) {
        const auto stamp =
            std::chrono::nanoseconds(1767225600s) + n * std::chrono::nanoseconds(kPeriod);
        test::DatagramBuilder builder("10.0.0.1", id, 4 * kTags);
        builder.request_id(static_cast<std::uint16_t>(n))
            .timestamp(static_cast<std::uint32_t>(stamp / 1s),
                       static_cast<std::uint32_t>((stamp % 1s).count()));
        for (int i = 0; i < kTags; ++i) {
            builder.set(std::to_string(4 * i) + ".0", TagType::dint,
                        core::plan::Value{std::int64_t{n} * (i + 1)});
        }
        return builder.build();
    }

    Pair pair_;
    test::SwitchedRole role_;
    northbound::FanOut fan_out_;
    std::vector<std::unique_ptr<ExchangeConsumer>> consumers_;
    std::vector<std::vector<std::byte>> datagrams_;
    std::size_t next_ = 0;
};

TEST(DatagramPathSteadyState, ADatagramAllocatesNothingOnceWarmWithoutAPair) {
    DatagramPath path(Pair::none);
    path.route(kWarm);
    const auto before = path.uns_.publisher.count;
    EXPECT_EQ(test::allocations_during([&] { path.route(kMeasured); }), 0u);
    EXPECT_EQ(path.uns_.publisher.count - before, std::size_t{kMeasured * kExchanges * kTags});
    EXPECT_EQ(path.router_.counters().accepted, std::uint64_t{(kWarm + kMeasured) * kExchanges});
}

TEST(DatagramPathSteadyState, ALeadersDatagramAllocatesNothingOnceWarm) {
    DatagramPath path(Pair::leader);
    path.route(kWarm);
    const auto before = path.uns_.publisher.count;
    EXPECT_EQ(test::allocations_during([&] { path.route(kMeasured); }), 0u);
    EXPECT_EQ(path.uns_.publisher.count - before, std::size_t{kMeasured * kExchanges * kTags});
    // Each exchange's watermark is its last datagram's sample: the tokens went out and came back.
    const auto marks = path.history_.watermarks();
    ASSERT_EQ(marks.size(), std::size_t{kExchanges});
    EXPECT_EQ(marks.at("turbine/e1").request_id, kWarm + kMeasured);
    EXPECT_EQ(path.history_.counters().window_overflow, 0u);
}

TEST(DatagramPathSteadyState, AStandbysDatagramAllocatesNothingOnceWarm) {
    DatagramPath path(Pair::standby);
    path.route(kWarm);
    EXPECT_EQ(test::allocations_during([&] { path.route(kMeasured); }), 0u);
    EXPECT_EQ(path.uns_.publisher.count, 0u);
    EXPECT_EQ(path.router_.counters().accepted, std::uint64_t{(kWarm + kMeasured) * kExchanges});
    // Its windows kept the samples: taking over, it publishes them on `_history`.
    path.history_.took_over(path.clock_.monotonic());
    EXPECT_GT(path.history_.counters().replayed, 0u);
    EXPECT_EQ(path.history_.counters().window_overflow, 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
