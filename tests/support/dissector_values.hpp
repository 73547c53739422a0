#pragma once
/// What the interop tests of the generated Wireshark plugin share: writing the plugin of a
/// configuration, and comparing a tag value as tshark prints it with the value the gateway
/// published on MQTT.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::test {

/// `eip2mqtt dissector -c CONFIG -o DIR/eip2mqtt.lua`; the plugin's path. The test fails when
/// the command does.
std::string write_dissector(const std::string& config_path, const std::string& dir);

/// `value` as tshark prints a float field (`%.6g`, FLT_DIG digits) or a double one (`%.15g`).
std::string as_tshark_prints(double value, int digits);

/// Whether tshark's text and the gateway's JSON value are the same value of `type`. Integers
/// and bits exactly; reals to the digits tshark prints (6 for binary32, 15 for binary64), the
/// gateway's value rounded the same way.
::testing::AssertionResult agree(core::plan::TagType type, const std::string& shown,
                                 const nlohmann::json& published);

}  // namespace eip2mqtt::test
