#pragma once
/// Loading configuration text in the tests of the YAML loader (tests/adapters/yaml/
/// load_config_test.cpp, read_sections_test.cpp, read_exchanges_test.cpp). For the tests only:
/// it adds its names to the namespace.

#include <gtest/gtest.h>

#include <string>

#include "eip2mqtt/adapters/yaml/load_config.hpp"

namespace eip2mqtt::adapters::yaml {

using core::config::Config;
using core::config::Diagnostics;
using core::plan::Direction;
using core::plan::TagType;

inline const std::string data = std::string(EIP2MQTT_TEST_DATA) + "/configs/";

inline std::string dump(const Diagnostics& diagnostics) {
    std::string out;
    for (const auto& d : diagnostics) {
        out += d.mark.file.str() + ":" + std::to_string(d.mark.line) + ":" +
               std::to_string(d.mark.column) + ": " + d.message + "\n";
    }
    return out;
}

/// Loads text that must be valid.
inline Config good(const std::string& text) {
    auto result = load_config_text(text, "test.yaml");
    EXPECT_TRUE(result.ok()) << dump(result.error());
    return result.ok() ? std::move(result).value() : Config{};
}

/// Loads text that must fail; returns its diagnostics.
inline Diagnostics bad(const std::string& text) {
    auto result = load_config_text(text, "test.yaml");
    EXPECT_FALSE(result.ok());
    return result.ok() ? Diagnostics{} : result.error();
}

inline const std::string minimal_exchange =
    "exchanges:\n"
    "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n";

}  // namespace eip2mqtt::adapters::yaml
