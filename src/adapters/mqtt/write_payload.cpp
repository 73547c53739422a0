#include "eip2mqtt/adapters/mqtt/write_payload.hpp"

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::adapters::mqtt {
namespace {

using core::write::WriteError;
using core::write::WriteInput;
using core::write::WriteRejection;
// Keeps the payload's key order, which parse_exchange_write promises.
using Json = nlohmann::ordered_json;

// Far above any real write (even every bit of a 1400-byte exchange written by name fits), and
// low enough that a hostile client cannot make us parse megabytes.
constexpr std::size_t max_payload_size = 256 * 1024;

const char* const malformed_json = "malformed JSON";
const char* const expected_scalar = "expected a JSON scalar or {\"value\": ...}";

WriteRejection reject(WriteError error, std::string message) { return {error, std::move(message)}; }

/// Parses `payload` without exceptions, and without building what no write may contain: arrays
/// anywhere, objects below the second level. nullopt (malformed) also on duplicate keys, which
/// nlohmann would silently resolve to the last one.
std::optional<Json> parse(std::string_view payload) {
    if (payload.size() > max_payload_size) return std::nullopt;
    // nlohmann's lexer takes a NUL byte for the end of input, which would accept "42\0junk";
    // a raw NUL is never valid JSON text.
    if (payload.find('\0') != std::string_view::npos) return std::nullopt;
    bool rejected = false;
    std::vector<std::set<std::string>> keys;  // keys seen by each open object, by depth
    const Json::parser_callback_t callback = [&](int depth, Json::parse_event_t event,
                                                 Json& parsed) {
        switch (event) {
            case Json::parse_event_t::array_start:
                rejected = true;
                return false;
            case Json::parse_event_t::object_start:
                // {"tag": {"value": 1}}: the second object opens at depth 1.
                if (depth >= 2) {
                    rejected = true;
                    return false;
                }
                keys.resize(static_cast<std::size_t>(depth) + 1);
                keys[static_cast<std::size_t>(depth)].clear();
                return true;
            case Json::parse_event_t::key: {
                // A key's depth counts its object, which opened one level up.
                const auto owner = static_cast<std::size_t>(depth - 1);
                if (depth < 1 || owner >= keys.size() ||
                    !keys[owner].insert(parsed.get_ref<const std::string&>()).second) {
                    rejected = true;
                    return false;
                }
                return true;
            }
            default:
                return !rejected;
        }
    };
    Json json = Json::parse(payload.begin(), payload.end(), callback, /*allow_exceptions=*/false);
    if (rejected || json.is_discarded()) return std::nullopt;
    return json;
}

/// What a client may send where a scalar is expected.
core::Result<WriteInput, WriteRejection> scalar(const Json& value) {
    switch (value.type()) {
        case Json::value_t::boolean:
            return WriteInput{value.get<bool>()};
        case Json::value_t::number_unsigned:
            return WriteInput{value.get<std::uint64_t>()};
        case Json::value_t::number_integer:
            return WriteInput{value.get<std::int64_t>()};
        case Json::value_t::number_float:
            // The parser rejects numbers beyond double's range, so this is finite.
            return WriteInput{value.get<double>()};
        case Json::value_t::string:
            return core::fail(
                reject(WriteError::wrong_type, "expected a number or true/false, got a string"));
        case Json::value_t::null:
            return core::fail(
                reject(WriteError::wrong_type, "expected a number or true/false, got null"));
        default:
            return core::fail(reject(WriteError::malformed, expected_scalar));
    }
}

/// A scalar, or {"value": scalar}.
core::Result<WriteInput, WriteRejection> tag_value(const Json& value) {
    if (!value.is_object()) return scalar(value);
    if (value.size() != 1 || !value.contains("value")) {
        return core::fail(reject(WriteError::malformed, expected_scalar));
    }
    const auto& inner = value.at("value");
    if (inner.is_object()) return core::fail(reject(WriteError::malformed, expected_scalar));
    return scalar(inner);
}

}  // namespace

core::Result<WriteInput, WriteRejection> parse_tag_write(std::string_view payload) {
    const auto json = parse(payload);
    if (!json) return core::fail(reject(WriteError::malformed, malformed_json));
    return tag_value(*json);
}

core::Result<std::vector<std::pair<std::string, WriteInput>>, WriteRejection> parse_exchange_write(
    std::string_view payload) {
    const auto json = parse(payload);
    if (!json) return core::fail(reject(WriteError::malformed, malformed_json));
    if (!json->is_object()) {
        return core::fail(
            reject(WriteError::malformed,
                   "expected a JSON object of tag names and values, e.g. {\"SPEED_SP\": 3100}"));
    }
    if (json->empty()) return core::fail(reject(WriteError::empty, "no tag to write"));
    std::vector<std::pair<std::string, WriteInput>> writes;
    writes.reserve(json->size());
    for (const auto& [name, value] : json->items()) {
        auto input = tag_value(value);
        if (!input) {
            return core::fail(reject(input.error().error, name + ": " + input.error().message));
        }
        writes.emplace_back(name, std::move(input).value());
    }
    return writes;
}

}  // namespace eip2mqtt::adapters::mqtt
