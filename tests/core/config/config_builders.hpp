#pragma once
/// Configurations for the tests of validate() (tests/core/config/config_test.cpp and
/// detail/*_test.cpp): every key of a built exchange or tag sits on its own fresh line, so that
/// a diagnostic can be located. For the tests only: it adds its names to the namespace.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::core::config {

using namespace std::chrono_literals;
using plan::Direction;
using plan::TagType;

/// The line the next key built is written on; valid() starts again at 1.
inline int next_line = 1;

inline Mark at(int line, int column = 1) { return {"c.yaml", line, column}; }

/// A tag whose every key sits on its own fresh line, so diagnostics can be located.
inline TagConfig tag(std::string name, std::uint16_t byte, std::uint8_t bit, TagType type) {
    TagConfig t;
    t.spec.name = std::move(name);
    t.spec.address = {byte, bit};
    t.spec.type = type;
    t.marks.node = at(next_line, 7);
    for (const char* key : {"name", "address", "type", "writable", "min", "max", "initial",
                            "deadband", "refresh_s"}) {
        t.marks.add(key, at(next_line++, 9));
    }
    return t;
}

inline ExchangeConfig exchange(std::string name, Direction direction, std::uint32_t id) {
    ExchangeConfig e;
    e.spec.name = name;
    e.spec.topic = name;
    e.spec.direction = direction;
    e.spec.producer_id = wire::ProducerId{0x7F000001};
    e.spec.exchange_id = id;
    e.spec.length = 16;
    e.spec.period = 100ms;
    if (direction == Direction::produce) e.spec.destination = "127.0.0.1";
    e.marks.node = at(next_line, 5);
    for (const char* key : {"name", "direction", "producer_id", "exchange_id", "length",
                            "period_ms", "timeout_ms", "source", "destination", "topic"}) {
        e.marks.add(key, at(next_line++, 5));
    }
    return e;
}

inline Config valid() {
    next_line = 1;
    Config c;
    c.file = "c.yaml";
    c.gateway.id = "gw";
    c.mqtt.base_topic = "acme/site";
    for (const char* key : {"url", "version", "qos", "base_topic"}) {
        c.mqtt.marks.add(key, at(next_line++, 3));
    }
    c.gateway.marks.add("id", at(next_line++, 3));
    c.gateway.marks.add("log_level", at(next_line++, 3));
    auto consumed = exchange("turbine1", Direction::consume, 2);
    consumed.tags.push_back(tag("RUNNING", 0, 0, TagType::bit));
    consumed.tags.push_back(tag("PRESSAO", 2, 0, TagType::int_));
    c.exchanges.push_back(consumed);
    auto produced = exchange("setpoints", Direction::produce, 10);
    produced.tags.push_back(tag("SPEED_SP", 0, 0, TagType::real));
    produced.tags.back().spec.writable = true;
    c.exchanges.push_back(produced);
    return c;
}

/// The one diagnostic expected; fails the test when there are none or more.
inline Diagnostic only(const Diagnostics& found) {
    EXPECT_EQ(found.size(), 1u);
    if (found.size() != 1) {
        for (const auto& d : found)
            ADD_FAILURE() << d.mark.line << ":" << d.mark.column << " " << d.message;
    }
    return found.empty() ? Diagnostic{} : found.front();
}

inline bool mentions(const Diagnostic& d, std::string_view text) {
    return d.message.find(text) != std::string::npos;
}

}  // namespace eip2mqtt::core::config
