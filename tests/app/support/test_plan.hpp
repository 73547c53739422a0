#pragma once
// Exchange plans for unit tests of the app layer: what a test does not name is the same
// everywhere (producer 10.0.0.1, exchange 1, destination 127.0.0.1, base topic "acme").

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::test {

inline core::plan::TagSpec test_tag(std::string name, std::uint16_t byte, core::plan::TagType type,
                                    bool writable = false) {
    core::plan::TagSpec tag;
    tag.name = std::move(name);
    tag.address = {byte, 0};
    tag.type = type;
    tag.writable = writable;
    return tag;
}

/// `length` data bytes; the topic is the name unless given.
inline core::plan::ExchangePlan test_plan(std::string name, core::plan::Direction direction,
                                          std::size_t length, std::vector<core::plan::TagSpec> tags,
                                          std::string topic = "") {
    core::plan::ExchangeSpec spec;
    spec.topic = topic.empty() ? name : std::move(topic);
    spec.name = std::move(name);
    spec.direction = direction;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = 1;
    spec.length = length;
    spec.destination = "127.0.0.1";
    spec.tags = std::move(tags);
    return core::plan::make_exchange_plan(std::move(spec), "acme");
}

/// Exchange `name` (producer 10.0.0.1, `exchange_id`, 4 data bytes) of one `tag`, whose
/// period (an hour) never comes due while a test runs: tests of the running set (Exchanges).
inline core::plan::ExchangePlan test_exchange(std::string name, core::plan::Direction direction,
                                              std::uint32_t exchange_id, core::plan::TagSpec tag) {
    core::plan::ExchangeSpec spec;
    spec.name = name;
    spec.topic = std::move(name);
    spec.direction = direction;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = exchange_id;
    spec.length = 4;
    spec.destination = "127.0.0.1";
    spec.period = std::chrono::hours(1);
    spec.tags = {std::move(tag)};
    return core::plan::make_exchange_plan(std::move(spec), "acme");
}

/// Produced exchange `sp` (producer 10.0.0.1, exchange 10) of one writable dint VALUE at byte 0,
/// whose period (an hour) never comes due in a unit test: a producer's own tests and those of
/// what hears or follows it. `length` 0: the end of VALUE.
inline core::plan::ExchangePlan test_produced_plan(std::string topic = "sp",
                                                   std::size_t length = 0) {
    core::plan::ExchangeSpec spec;
    spec.name = "sp";
    spec.topic = std::move(topic);
    spec.direction = core::plan::Direction::produce;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = 10;
    spec.destination = "127.0.0.1";
    spec.period = std::chrono::hours(1);
    if (length > 0) spec.length = static_cast<std::uint16_t>(length);
    spec.tags = {test_tag("VALUE", 0, core::plan::TagType::dint, true)};
    return core::plan::make_exchange_plan(std::move(spec), "acme");
}

}  // namespace eip2mqtt::test
