// Fuzzes the datagram decoder with arbitrary UDP payloads, then drives ConsumedExchange with each
// datagram that decodes, as the gateway does: against a plan that matches its length (the accept
// path) and one that does not (the mismatch path), with the tags of every type read back from the
// consumed image, repeated (duplicate), timed out and recovered.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "eip2mqtt/core/exchange/consumed_exchange.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"

namespace {

using namespace eip2mqtt::core;

plan::ExchangePlan plan_for(const wire::Header& header, std::size_t length) {
    plan::ExchangeSpec spec;
    spec.name = "fuzz";
    spec.producer_id = header.producer_id;
    spec.exchange_id = header.exchange_id;
    spec.length = static_cast<std::uint16_t>(length);
    spec.period = std::chrono::milliseconds(100);
    spec.timeout = std::chrono::milliseconds(300);
    // The configured signature comes from the status field, so that every signature rule is
    // reachable: equal, other major, older or newer minor, unset.
    spec.signature = wire::Signature::from_wire(header.status);
    spec.topic = "fuzz";
    // One tag of each type at the last offset where it fits, and a bit in the last byte.
    for (const auto type :
         {plan::TagType::byte, plan::TagType::int_, plan::TagType::word, plan::TagType::dint,
          plan::TagType::udint, plan::TagType::real, plan::TagType::lint, plan::TagType::lreal}) {
        if (plan::size_of(type) > length) continue;
        plan::TagSpec tag;
        tag.name = std::string(plan::to_string(type));
        tag.type = type;
        tag.address.byte = static_cast<std::uint16_t>(length - plan::size_of(type));
        spec.tags.push_back(tag);
    }
    plan::TagSpec bit;
    bit.name = "bit";
    bit.type = plan::TagType::bit;
    bit.address = {static_cast<std::uint16_t>(length - 1), 7};
    spec.tags.push_back(bit);
    return plan::make_exchange_plan(spec, "fuzz");
}

void consume(const wire::Datagram& datagram, std::size_t length) {
    const auto plan = plan_for(datagram.header, length);
    exchange::ConsumedExchange consumer(plan);
    const MonoTime t0{};
    const auto read_tags = [&] {
        if (!consumer.has_image()) return;
        const auto image = consumer.image();
        if (image.size() != plan.length) __builtin_trap();
        for (const auto& tag : plan.tags) {
            (void)plan::decode_value(image, tag.spec.type, tag.spec.address);
        }
    };
    consumer.on_datagram(datagram, t0);
    read_tags();
    // The same datagram again is a duplicate; after the timeout it resynchronises.
    consumer.on_datagram(datagram, t0 + std::chrono::milliseconds(10));
    consumer.on_tick(t0 + std::chrono::seconds(1));
    (void)consumer.next_deadline();
    consumer.on_datagram(datagram, t0 + std::chrono::seconds(2));
    read_tags();
    const auto& c = consumer.counters();
    if (c.received != 3 || c.accepted > 3) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(data), size);
    const auto decoded = wire::decode_datagram(bytes);
    if (!decoded) {
        (void)wire::to_string(decoded.error());
        return 0;
    }
    const auto& datagram = decoded.value();
    if (datagram.data.empty() || datagram.data.size() > wire::max_data_size) __builtin_trap();
    (void)wire::to_string(datagram.header.producer_id);
    consume(datagram, datagram.data.size());
    // A configured length that differs: shorter (a newer minor may append data) or longer.
    consume(datagram, std::max<std::size_t>(1, datagram.data.size() / 2));
    consume(datagram, std::min(wire::max_data_size, datagram.data.size() + 1));
    return 0;
}
