#include "eip2mqtt/app/northbound/json_tree/write_payload.hpp"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace eip2mqtt::app::northbound::json_tree {
namespace {

using core::config::PayloadFormat;
using core::write::ScalarInput;
using core::write::WriteError;
using core::write::WriteInput;
using core::write::WriteRejection;
// Keeps the payload's key order, which parse_exchange_write promises.
using Json = nlohmann::ordered_json;

// Far above any real write (even every bit of a 1400-byte exchange written by name fits), and
// low enough that a hostile client cannot make us parse megabytes.
constexpr std::size_t max_payload_size = 256 * 1024;

const char* const malformed_json = "malformed JSON";
const char* const expected_scalar =
    "expected a JSON scalar, an array, {\"value\": ...} or {\"index\": i, \"value\": ...}";

WriteRejection reject(WriteError error, std::string message) { return {error, std::move(message)}; }

/// The exact integer a JSON number denotes, whatever its spelling (`12.0`, `1e3`,
/// `-9223372036854775808.0`), or nullopt when it has a fractional part or lies beyond 64 bits.
/// A double cannot tell: 9007199254740992.5 and -9223372036854775809 both round to integers.
std::optional<ScalarInput> exact_integer(std::string_view text) {
    std::size_t i = 0;
    const bool negative = i < text.size() && text[i] == '-';
    if (negative) ++i;
    std::string digits;  // integer and fraction digits, without the point
    long long exponent = 0;
    for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) digits += text[i];
    if (i < text.size() && text[i] == '.') {
        for (++i; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
            digits += text[i];
            --exponent;
        }
    }
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        const bool negative_exponent = i < text.size() && text[i] == '-';
        if (i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
        long long written = 0;
        for (; i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
            // Saturated: anything past a few hundred digits either way means "not an integer of
            // 64 bits" unless every digit is 0, which the value check below sees.
            written = std::min<long long>(written * 10 + (text[i] - '0'), 100000);
        }
        exponent += negative_exponent ? -written : written;
    }
    const auto first = digits.find_first_not_of('0');
    if (first == std::string::npos) return ScalarInput{std::uint64_t{0}};
    digits.erase(0, first);
    while (exponent < 0) {
        if (digits.back() != '0') return std::nullopt;  // a fractional part
        digits.pop_back();
        ++exponent;
    }
    if (static_cast<long long>(digits.size()) + exponent > 20) return std::nullopt;
    unsigned __int128 value = 0;
    for (const char c : digits) value = value * 10 + static_cast<unsigned>(c - '0');
    for (long long e = 0; e < exponent; ++e) value *= 10;
    constexpr auto u64_max = std::numeric_limits<std::uint64_t>::max();
    constexpr auto i64_min_magnitude = std::uint64_t{1} << 63;
    if (!negative) {
        if (value > u64_max) return std::nullopt;
        return ScalarInput{static_cast<std::uint64_t>(value)};
    }
    if (value > i64_min_magnitude) return std::nullopt;
    return ScalarInput{static_cast<std::int64_t>(-static_cast<std::int64_t>(value - 1) - 1)};
}

/// Builds the JSON of a write with nlohmann's SAX interface rather than its DOM parser, for
/// two reasons: a number's text is still at hand (see exact_integer), and what no write may
/// contain is refused before it is built: arrays within arrays or holding objects, objects
/// below the second level, duplicate keys (which nlohmann would silently resolve to the last
/// one).
class WriteBuilder final : public nlohmann::json_sax<Json> {
public:
    /// `records`: a top-level array may hold flat objects (Kepware's `[{"id":…,"v":…}]`).
    explicit WriteBuilder(bool records = false) : records_(records) {}

    Json root;

    bool null() override { return put(nullptr); }
    bool boolean(bool value) override { return put(value); }
    bool number_integer(number_integer_t value) override { return put(value); }
    bool number_unsigned(number_unsigned_t value) override { return put(value); }
    bool number_float(number_float_t value, const string_t& text) override {
        if (auto exact = exact_integer(text)) {
            return std::visit([&](auto v) { return put(v); }, *exact);
        }
        return put(value);
    }
    bool string(string_t& value) override { return put(std::move(value)); }
    bool binary(binary_t&) override { return false; }
    bool start_object(std::size_t) override {
        if (array_ != nullptr) {
            // A record of a top-level array, holding no object or array itself.
            if (!records_ || array_ != &root || record_ != nullptr) return false;
            array_->push_back(Json::object());
            record_ = &array_->back();
            open_.push_back({record_, {}});
            return true;
        }
        // {"tag": {"value": 1}}: two levels at most.
        if (open_.size() >= 2) return false;
        Json* object = open_.empty() ? &root : &slot();
        *object = Json::object();
        open_.push_back({object, {}});
        return true;
    }
    bool key(string_t& name) override {
        if (!open_.back().keys.insert(name).second) return false;
        key_ = std::move(name);
        return true;
    }
    bool end_object() override {
        open_.pop_back();
        if (open_.empty()) record_ = nullptr;
        return true;
    }
    bool start_array(std::size_t) override {
        // An array tag's elements: scalars only.
        if (array_ != nullptr) return false;
        array_ = open_.empty() ? &root : &slot();
        *array_ = Json::array();
        return true;
    }
    bool end_array() override {
        array_ = nullptr;
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

private:
    struct Open {
        Json* object;
        std::set<std::string> keys;
    };
    /// Where the next value goes: the key just read in the innermost open object.
    Json& slot() { return (*open_.back().object)[key_]; }
    template <class T>
    bool put(T&& value) {
        if (array_ != nullptr && record_ == nullptr) {
            array_->push_back(std::forward<T>(value));
        } else {
            (open_.empty() ? root : slot()) = std::forward<T>(value);
        }
        return true;
    }

    std::vector<Open> open_;
    std::string key_;
    Json* array_ = nullptr;  ///< the array being filled
    bool records_ = false;
    Json* record_ = nullptr;  ///< the record of `array_` being filled
};

/// Parses `payload` without exceptions; a rejection says why it cannot be a write.
core::Result<Json, WriteRejection> parse(std::string_view payload, bool records = false) {
    if (payload.size() > max_payload_size) {
        return core::fail(reject(WriteError::too_large,
                                 "payload too large (" + std::to_string(payload.size()) +
                                     " bytes, limit " + std::to_string(max_payload_size) + ")"));
    }
    // nlohmann's lexer takes a NUL byte for the end of input, which would accept "42\0junk";
    // a raw NUL is never valid JSON text.
    if (payload.find('\0') != std::string_view::npos) {
        return core::fail(reject(WriteError::malformed, malformed_json));
    }
    WriteBuilder builder(records);
    if (!Json::sax_parse(payload.begin(), payload.end(), &builder)) {
        return core::fail(reject(WriteError::malformed, malformed_json));
    }
    return std::move(builder.root);
}

/// A number or a boolean.
core::Result<ScalarInput, WriteRejection> scalar(const Json& value) {
    switch (value.type()) {
        case Json::value_t::boolean:
            return ScalarInput{value.get<bool>()};
        case Json::value_t::number_unsigned:
            return ScalarInput{value.get<std::uint64_t>()};
        case Json::value_t::number_integer:
            return ScalarInput{value.get<std::int64_t>()};
        case Json::value_t::number_float:
            // The parser rejects numbers beyond double's range, so this is finite.
            return ScalarInput{value.get<double>()};
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

/// A scalar, a string's text, or an array tag's elements.
core::Result<WriteInput, WriteRejection> plain_value(const Json& value) {
    if (value.is_string()) return WriteInput{value.get<std::string>()};
    if (value.is_array()) {
        core::write::ArrayInput array;
        array.items.reserve(value.size());
        for (std::size_t i = 0; i < value.size(); ++i) {
            auto item = scalar(value[i]);
            if (!item) {
                auto rejection = item.error();
                rejection.message = "element " + std::to_string(i) + ": " + rejection.message;
                return core::fail(std::move(rejection));
            }
            array.items.push_back(std::move(item).value());
        }
        return WriteInput{std::move(array)};
    }
    auto one = scalar(value);
    if (!one) return core::fail(one.error());
    return std::visit([](auto v) { return WriteInput{v}; }, one.value());
}

/// {"index": i, "value": scalar}: one element of an array tag.
core::Result<WriteInput, WriteRejection> element_value(const Json& value) {
    const auto& index = value.at("index");
    if (!index.is_number_unsigned() || index.get<std::uint64_t>() > 0xFFFF) {
        return core::fail(reject(WriteError::wrong_type, "index must be an integer of 0 or more"));
    }
    auto one = scalar(value.at("value"));
    if (!one) return core::fail(one.error());
    return WriteInput{core::write::ElementInput{
        static_cast<std::uint16_t>(index.get<std::uint64_t>()), std::move(one).value()}};
}

/// A plain value, {"value": plain value}, or {"index": i, "value": scalar}.
core::Result<WriteInput, WriteRejection> tag_value(const Json& value) {
    if (!value.is_object()) return plain_value(value);
    if (value.size() == 2 && value.contains("index") && value.contains("value")) {
        return element_value(value);
    }
    if (value.size() != 1 || !value.contains("value")) {
        return core::fail(reject(WriteError::malformed, expected_scalar));
    }
    const auto& inner = value.at("value");
    if (inner.is_object()) return core::fail(reject(WriteError::malformed, expected_scalar));
    return plain_value(inner);
}

/// A profile's own form of one tag's write, as the json profile's: umh's
/// `{"value":…,"timestamp_ms":…}` (the time is the gateway's to give) and Kepware's `{"v":…}`.
Json in_json_form(Json value, PayloadFormat profile) {
    if (!value.is_object()) return value;
    if (profile == PayloadFormat::umh && value.size() == 2 && value.contains("value") &&
        value.contains("timestamp_ms") && value.at("timestamp_ms").is_number()) {
        value.erase("timestamp_ms");
    } else if (profile == PayloadFormat::kepware && value.size() == 1 && value.contains("v")) {
        return Json{{"value", std::move(value.at("v"))}};
    }
    return value;
}

/// Kepware's write: `[{"id":"exchange.tag","v":…},…]`, each id as it was written.
core::Result<std::vector<NamedWrite>, WriteRejection> kepware_records(const Json& records) {
    if (records.empty()) return core::fail(reject(WriteError::empty, "no tag to write"));
    std::vector<NamedWrite> writes;
    writes.reserve(records.size());
    for (const auto& record : records) {
        if (!record.is_object() || record.size() != 2 || !record.contains("id") ||
            !record.at("id").is_string() || !record.contains("v")) {
            return core::fail(reject(WriteError::malformed,
                                     "expected [{\"id\": \"exchange.tag\", \"v\": value}, …]"));
        }
        auto input = plain_value(record.at("v"));
        const auto& id = record.at("id").get_ref<const std::string&>();
        if (!input) {
            return core::fail(reject(input.error().error, id + ": " + input.error().message));
        }
        writes.emplace_back(id, std::move(input).value());
    }
    return writes;
}

}  // namespace

core::Result<WriteInput, WriteRejection> parse_tag_write(std::string_view payload,
                                                         PayloadFormat profile) {
    auto json = parse(payload);
    if (!json) {
        // The value profile publishes a string bare, and takes it back so.
        if (profile == PayloadFormat::value && json.error().error == WriteError::malformed &&
            !payload.empty() && payload.find('\0') == std::string_view::npos) {
            return WriteInput{std::string(payload)};
        }
        return core::fail(json.error());
    }
    return tag_value(in_json_form(std::move(json).value(), profile));
}

core::Result<std::vector<NamedWrite>, WriteRejection> parse_exchange_write(std::string_view payload,
                                                                           PayloadFormat profile) {
    const bool kepware = profile == PayloadFormat::kepware;
    const auto parsed = parse(payload, kepware);
    if (!parsed) return core::fail(parsed.error());
    const Json* json = &parsed.value();
    if (kepware && json->is_array()) return kepware_records(*json);
    if (!json->is_object()) {
        return core::fail(
            reject(WriteError::malformed,
                   "expected a JSON object of tag names and values, e.g. {\"SPEED_SP\": 3100}"));
    }
    if (json->empty()) return core::fail(reject(WriteError::empty, "no tag to write"));
    std::vector<NamedWrite> writes;
    writes.reserve(json->size());
    for (const auto& [name, value] : json->items()) {
        auto input = tag_value(in_json_form(value, profile));
        if (!input) {
            return core::fail(reject(input.error().error, name + ": " + input.error().message));
        }
        writes.emplace_back(name, std::move(input).value());
    }
    return writes;
}

}  // namespace eip2mqtt::app::northbound::json_tree
