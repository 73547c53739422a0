// A SparkplugNode over a publisher that only measures: its births, made the way the gateway
// makes them, with every value at its widest, give `check` their size.

#include "eip2mqtt/app/northbound/sparkplug/sparkplug_birth_size.hpp"

#include <chrono>
#include <string>

#include "eip2mqtt/adapters/mqtt/publisher.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using core::plan::TagType;
using core::plan::Value;

class MeasuringPublisher final : public adapters::mqtt::Publisher {
public:
    void publish(adapters::mqtt::Message&& message) override {
        last = adapters::mqtt::publish_packet_bytes(message);
        message.clear();
    }
    void set_subscriptions(std::vector<std::string>) override {}
    std::size_t last = 0;
};

class NoWrites final : public WriteHandler {
public:
    void on_write(WriteRequest&&) override {}
};

// Milliseconds since 1970 take 6 bytes of varint until the year 2109.
constexpr std::int64_t widest_time_ms = (std::int64_t{1} << 42) - 1;

/// Always the time whose encoding is the longest.
class WidestClock final : public core::Clock {
public:
    core::MonoTime monotonic() const override { return {}; }
    core::WallTime wall() const override {
        return core::WallTime{std::chrono::milliseconds(widest_time_ms)};
    }
};

/// The value of `type` whose Sparkplug encoding is the longest: signed types travel as two's
/// complement, so -1 takes every byte of its varint.
Value widest_scalar(TagType type) {
    switch (type) {
        case TagType::bit:
            return Value{true};
        case TagType::byte:
            return Value{std::uint64_t{0xff}};
        case TagType::word:
            return Value{std::uint64_t{0xffff}};
        case TagType::udint:
            return Value{std::uint64_t{0xffffffff}};
        case TagType::real:
            return Value{1.0f};
        case TagType::lreal:
            return Value{1.0};
        case TagType::int_:
        case TagType::dint:
        case TagType::lint:
        case TagType::string:
            return Value{std::int64_t{-1}};
    }
    return Value{std::int64_t{-1}};
}

/// A string's longest text is two UTF-8 bytes for each of its Latin-1 bytes.
Value widest_value(const core::plan::TagSpec& tag) {
    if (tag.type == TagType::string) return core::plan::make_text(std::string(2 * tag.count, 'x'));
    if (!tag.is_array()) return widest_scalar(tag.type);
    return core::plan::make_list(std::vector<Value>(tag.count, widest_scalar(tag.type)));
}

}  // namespace

SparkplugBirthSizes sparkplug_birth_sizes(const SparkplugOptions& options,
                                          std::span<const core::plan::ExchangePlan> plans) {
    MeasuringPublisher publisher;
    NoWrites writes;
    SparkplugOptions measured = options;
    measured.primary_host_id.clear();
    measured.max_packet_bytes = 0;
    const WidestClock clock;
    SparkplugNode node(std::move(measured), publisher, writes, clock, [] {});
    ExchangeSet running;
    for (const auto& plan : plans) {
        (plan.spec.direction == core::plan::Direction::produce ? running.produced
                                                               : running.consumed)
            .push_back(&plan);
    }
    node.exchanges_changed(running, {});
    node.widen_node_metrics_for_sizing();
    node.next_will();
    node.on_connected();
    SparkplugBirthSizes sizes;
    sizes.node = publisher.last;
    std::vector<TagSample> samples;
    for (const auto& plan : plans) {
        samples.clear();
        for (std::size_t i = 0; i < plan.tags.size(); ++i) {
            samples.push_back({i, widest_value(plan.tags[i].spec)});
        }
        publisher.last = 0;
        node.tag_samples({plan, core::quality::Quality::good, widest_time_ms, false, samples});
        node.exchange_state(plan, core::exchange::ConsumeState::ok);
        sizes.devices.push_back(publisher.last);
    }
    return sizes;
}

}  // namespace eip2mqtt::app::northbound::sparkplug
