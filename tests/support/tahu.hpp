#pragma once
/// Sparkplug B payloads through Eclipse Tahu's JavaScript library (tests/support/tahu/tahu.js,
/// run by Node.js): an implementation we did not write reads what the gateway publishes and
/// writes what a host would send it.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace eip2mqtt::test {

/// The payload as Tahu decodes it: {"timestamp": "..", "seq": "..", "metrics": [{"name",
/// "alias", "type", "value", "timestamp", "properties"}..]}, 64-bit integers as strings.
nlohmann::json tahu_decode(const std::string& bytes);

/// Each of `payloads` as tahu_decode() gives it, in order, with one run of Node.js: many
/// messages decoded one by one would take a Node.js start each. Always as many as `payloads`
/// (empty objects, the test failed, when Tahu could not decode them all).
std::vector<nlohmann::json> tahu_decode_all(const std::vector<std::string>& payloads);

/// The metric `name` of a decoded payload; an empty object, and a failure of the test, without
/// one.
nlohmann::json tahu_metric(const nlohmann::json& payload, const std::string& name);

/// The protobuf bytes Tahu encodes for `payload` ({"timestamp": ms, "metrics": [{"name",
/// "alias", "type", "value"}..]}).
std::string tahu_encode(const nlohmann::json& payload);

}  // namespace eip2mqtt::test
