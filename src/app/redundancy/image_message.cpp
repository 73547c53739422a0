#include "eip2mqtt/app/redundancy/image_message.hpp"

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <vector>

namespace eip2mqtt::app::redundancy {
namespace {

constexpr std::string_view digits = "0123456789abcdef";

std::string to_hex(std::span<const std::byte> bytes) {
    std::string out;
    out.reserve(bytes.size() * 2);
    for (const auto b : bytes) {
        const auto value = static_cast<std::uint8_t>(b);
        out += digits[value >> 4];
        out += digits[value & 0x0F];
    }
    return out;
}

std::optional<std::uint8_t> nibble(char c) {
    if (c >= '0' && c <= '9') return static_cast<std::uint8_t>(c - '0');
    if (c >= 'a' && c <= 'f') return static_cast<std::uint8_t>(c - 'a' + 10);
    if (c >= 'A' && c <= 'F') return static_cast<std::uint8_t>(c - 'A' + 10);
    return std::nullopt;
}

std::optional<std::vector<std::byte>> from_hex(std::string_view text) {
    if (text.size() % 2 != 0) return std::nullopt;
    std::vector<std::byte> out;
    out.reserve(text.size() / 2);
    for (std::size_t i = 0; i < text.size(); i += 2) {
        const auto high = nibble(text[i]);
        const auto low = nibble(text[i + 1]);
        if (!high || !low) return std::nullopt;
        out.push_back(static_cast<std::byte>(*high << 4 | *low));
    }
    return out;
}

std::string hex16(std::uint64_t value) {
    std::string out(16, '0');
    for (std::size_t i = 0; i < 16; ++i) out[15 - i] = digits[(value >> (4 * i)) & 0x0F];
    return out;
}

std::optional<std::uint64_t> from_hex16(std::string_view text) {
    if (text.size() != 16) return std::nullopt;
    std::uint64_t layout = 0;
    for (const char c : text) {
        const auto value = nibble(c);
        if (!value) return std::nullopt;
        layout = layout << 4 | *value;
    }
    return layout;
}

/// The keys listed under `name` (`answers`, `refused`): nullopt when absent (an image of a unit
/// that answered none, or of an older release); `bad` set when present and not a list of keys.
std::optional<std::vector<std::uint64_t>> keys_at(const nlohmann::json& json, const char* name,
                                                  bool& bad) {
    const auto found = json.find(name);
    if (found == json.end()) return std::nullopt;
    std::vector<std::uint64_t> keys;
    if (!found->is_array()) bad = true;
    if (bad) return keys;
    keys.reserve(found->size());
    for (const auto& item : *found) {
        const auto key =
            item.is_string() ? from_hex16(item.get_ref<const std::string&>()) : std::nullopt;
        if (!key) {
            bad = true;
            break;
        }
        keys.push_back(*key);
    }
    return keys;
}

void put_keys(nlohmann::json& json, const char* name, const std::vector<std::uint64_t>& keys) {
    auto& list = json[name] = nlohmann::json::array();
    for (const auto key : keys) list.push_back(hex16(key));
}

const std::string* string_at(const nlohmann::json& json, const char* key) {
    const auto it = json.find(key);
    return it != json.end() && it->is_string() ? &it->get_ref<const std::string&>() : nullptr;
}

}  // namespace

std::string encode_image_message(const core::redundancy::ImageMessage& image) {
    nlohmann::json json{{"id", image.id},
                        {"epoch", image.epoch},
                        {"layout", hex16(image.layout)},
                        {"data", to_hex(image.data)}};
    if (!image.answers.empty()) {
        put_keys(json, "answers", image.answers);
        if (image.refused) put_keys(json, "refused", *image.refused);
    }
    if (image.seq != 0) json["seq"] = image.seq;
    return json.dump();
}

std::optional<core::redundancy::ImageMessage> decode_image_message(std::string_view payload) {
    if (payload.empty()) return std::nullopt;
    const auto json = nlohmann::json::parse(payload, nullptr, false);
    if (!json.is_object()) return std::nullopt;
    const auto* id = string_at(json, "id");
    const auto* layout_text = string_at(json, "layout");
    const auto* data_text = string_at(json, "data");
    const auto epoch = json.find("epoch");
    if (!id || !layout_text || !data_text || epoch == json.end() || !epoch->is_number_unsigned()) {
        return std::nullopt;
    }
    const auto layout = from_hex16(*layout_text);
    auto data = from_hex(*data_text);
    bool bad_keys = false;
    auto answers = keys_at(json, "answers", bad_keys);
    auto refused = keys_at(json, "refused", bad_keys);
    const auto seq = json.find("seq");
    const bool seq_ok = seq == json.end() || seq->is_number_unsigned();
    if (!layout || !data || bad_keys || !seq_ok) return std::nullopt;
    return core::redundancy::ImageMessage{*id,
                                          epoch->get<std::uint64_t>(),
                                          *layout,
                                          std::move(*data),
                                          std::move(answers).value_or(std::vector<std::uint64_t>{}),
                                          seq == json.end() ? 0 : seq->get<std::uint64_t>(),
                                          std::move(refused)};
}

}  // namespace eip2mqtt::app::redundancy
