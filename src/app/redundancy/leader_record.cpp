#include "eip2mqtt/app/redundancy/leader_record.hpp"

#include <nlohmann/json.hpp>

namespace eip2mqtt::app::redundancy {
namespace {

nlohmann::json encode_key(const core::redundancy::SampleKey& key) {
    auto json = nlohmann::json::array({key.request_id, key.time_s, key.time_ns});
    if (key.change != 0) json.push_back(key.change);
    return json;
}

/// Element `i` of `json` if it is an unsigned number of at most `max`.
std::optional<std::uint64_t> element(const nlohmann::json& json, std::size_t i, std::uint64_t max) {
    if (i >= json.size() || !json[i].is_number_unsigned()) return std::nullopt;
    const auto value = json[i].get<std::uint64_t>();
    if (value > max) return std::nullopt;
    return value;
}

std::optional<core::redundancy::SampleKey> decode_key(const nlohmann::json& json) {
    if (!json.is_array() || json.size() < 3 || json.size() > 4) return std::nullopt;
    const auto request_id = element(json, 0, 0xffff);
    const auto time_s = element(json, 1, 0xffffffff);
    const auto time_ns = element(json, 2, 999'999'999);
    const auto change = json.size() == 4 ? element(json, 3, 0xff) : std::optional<std::uint64_t>(0);
    if (!request_id || !time_s || !time_ns || !change) return std::nullopt;
    return core::redundancy::SampleKey{
        static_cast<std::uint16_t>(*request_id), static_cast<std::uint32_t>(*time_s),
        static_cast<std::uint32_t>(*time_ns), static_cast<std::uint8_t>(*change)};
}

void decode_watermarks(const nlohmann::json& record, Watermarks& watermarks) {
    watermarks.clear();
    const auto found = record.find("watermarks");
    if (found == record.end() || !found->is_object()) return;
    for (const auto& [topic, key] : found->items()) {
        if (const auto decoded = decode_key(key)) watermarks.emplace(topic, *decoded);
    }
}

std::optional<core::redundancy::LeaderMark> decode_mark(const nlohmann::json& record) {
    const auto found = record.find("heard");
    if (found == record.end() || !found->is_object()) return std::nullopt;
    const auto id = found->find("id");
    const auto epoch = found->find("epoch");
    const auto beat = found->find("beat");
    if (id == found->end() || !id->is_string() || epoch == found->end() ||
        !epoch->is_number_unsigned() || beat == found->end() || !beat->is_number_unsigned()) {
        return std::nullopt;
    }
    return core::redundancy::LeaderMark{id->get<std::string>(), epoch->get<std::uint64_t>(),
                                        beat->get<std::uint64_t>()};
}

}  // namespace

std::string encode_leader_record(const core::redundancy::LeaderRecord& record,
                                 std::chrono::milliseconds takeover, const Watermarks& watermarks) {
    nlohmann::json json{{"id", record.id},
                        {"epoch", record.epoch},
                        {"priority", record.priority},
                        {"takeover_ms", takeover.count()}};
    if (record.claim) json["claim"] = true;
    if (record.bd_seq) json["bd_seq"] = *record.bd_seq;
    if (record.beat != 0) json["beat"] = record.beat;
    if (record.heard) {
        json["heard"] = {
            {"id", record.heard->id}, {"epoch", record.heard->epoch}, {"beat", record.heard->beat}};
    }
    if (!watermarks.empty()) {
        auto& marks = json["watermarks"] = nlohmann::json::object();
        for (const auto& [topic, key] : watermarks) marks[topic] = encode_key(key);
    }
    return json.dump();
}

std::optional<core::redundancy::LeaderRecord> decode_leader_record(std::string_view payload,
                                                                   Watermarks* watermarks) {
    if (payload.empty()) return std::nullopt;
    const auto json = nlohmann::json::parse(payload, nullptr, false);
    if (!json.is_object()) return std::nullopt;
    const auto id = json.find("id");
    const auto epoch = json.find("epoch");
    if (id == json.end() || !id->is_string() || id->get_ref<const std::string&>().empty() ||
        epoch == json.end() || !epoch->is_number_unsigned()) {
        return std::nullopt;
    }
    core::redundancy::LeaderRecord record{id->get<std::string>(), epoch->get<std::uint64_t>(), 0};
    if (const auto priority = json.find("priority"); priority != json.end() &&
                                                     priority->is_number_unsigned() &&
                                                     priority->get<std::uint64_t>() <= 65535) {
        record.priority = static_cast<int>(priority->get<std::uint64_t>());
    }
    if (const auto claim = json.find("claim"); claim != json.end() && claim->is_boolean()) {
        record.claim = claim->get<bool>();
    }
    // Anything else is no bdSeq: the unit taking over then takes its own next.
    if (const auto bd_seq = json.find("bd_seq"); bd_seq != json.end() &&
                                                 bd_seq->is_number_unsigned() &&
                                                 bd_seq->get<std::uint64_t>() <= 255) {
        record.bd_seq = static_cast<std::uint8_t>(bd_seq->get<std::uint64_t>());
    }
    // Of an earlier version: beat 0, and a claim that names nothing (stale to a live leader).
    if (const auto beat = json.find("beat"); beat != json.end() && beat->is_number_unsigned()) {
        record.beat = beat->get<std::uint64_t>();
    }
    if (record.claim) record.heard = decode_mark(json);
    if (watermarks) decode_watermarks(json, *watermarks);
    return record;
}

}  // namespace eip2mqtt::app::redundancy
