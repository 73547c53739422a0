// Fuzzes what a Sparkplug host (or anyone allowed to publish there) sends the edge node: the
// first byte picks the topic (NCMD, a DCMD to a produced or a consumed exchange, an unknown
// device, the primary host's STATE), the rest is the payload. Whatever it is, the node must
// neither throw nor crash, and a write it accepts names only tags of the exchange it addresses.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

namespace {

using namespace eip2mqtt;

class NullPublisher final : public adapters::mqtt::Publisher {
public:
    void publish(adapters::mqtt::Message&& message) override { message.clear(); }
    void set_subscriptions(std::vector<std::string>) override {}
};

class CheckingWrites final : public app::WriteHandler {
public:
    explicit CheckingWrites(const core::plan::ExchangePlan& produced) : produced_(produced) {}
    void on_write(app::WriteRequest&& request) override {
        if (request.reply.origin == nullptr) __builtin_trap();
        const auto* write = std::get_if<app::ExchangeWrite>(&request.outcome);
        if (write == nullptr) return;
        if (write->producer != &produced_ || write->writes.empty()) __builtin_trap();
        for (const auto& tag : write->writes) {
            if (tag.tag_index >= produced_.tags.size()) __builtin_trap();
        }
    }

private:
    const core::plan::ExchangePlan& produced_;
};

core::plan::ExchangePlan make_plan(const char* name, core::plan::Direction direction) {
    core::plan::ExchangeSpec spec;
    spec.name = name;
    spec.topic = name;
    spec.direction = direction;
    spec.exchange_id = 1;
    spec.length = 8;
    spec.destination = "127.0.0.1";
    core::plan::TagSpec word;
    word.name = "W";
    word.address = {0, 0};
    word.type = core::plan::TagType::word;
    word.writable = true;
    core::plan::TagSpec bit = word;
    bit.name = "B";
    bit.type = core::plan::TagType::bit;
    core::plan::TagSpec real = word;
    real.name = "R";
    real.address = {4, 0};
    real.type = core::plan::TagType::real;
    spec.tags = {word, bit, real};
    return core::plan::make_exchange_plan(std::move(spec), "f");
}

/// Payload timestamps at one fixed time, so that a crash replays alike.
class FixedClock final : public core::Clock {
public:
    core::MonoTime monotonic() const override { return {}; }
    core::WallTime wall() const override {
        return core::WallTime{std::chrono::milliseconds(1700000000000)};
    }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    static const auto consumed = make_plan("in", core::plan::Direction::consume);
    static const auto produced = make_plan("out", core::plan::Direction::produce);
    static const char* const topics[] = {"spBv1.0/g/NCMD/n", "spBv1.0/g/DCMD/n/out",
                                         "spBv1.0/g/DCMD/n/in", "spBv1.0/g/DCMD/n/nowhere",
                                         "spBv1.0/STATE/host"};
    NullPublisher publisher;
    CheckingWrites writes(produced);
    const FixedClock clock;
    app::northbound::sparkplug::SparkplugNode node({"g", "n", "host", 0, std::nullopt}, publisher,
                                                   writes, clock, [] {});
    node.exchanges_changed({{&consumed}, {&produced}}, {});
    node.next_will();
    node.on_connected();
    adapters::mqtt::Incoming message;
    message.topic = topics[data[0] % (sizeof(topics) / sizeof(topics[0]))];
    message.retained = (data[0] & 0x80) != 0;
    message.payload.assign(reinterpret_cast<const char*>(data) + 1, size - 1);
    node.on_message(message);
    return 0;
}
