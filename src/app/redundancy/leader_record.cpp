#include "eip2mqtt/app/redundancy/leader_record.hpp"

#include <nlohmann/json.hpp>

namespace eip2mqtt::app::redundancy {

std::string encode_leader_record(const core::redundancy::LeaderRecord& record,
                                 std::chrono::milliseconds takeover) {
    nlohmann::json json{{"id", record.id},
                        {"epoch", record.epoch},
                        {"priority", record.priority},
                        {"takeover_ms", takeover.count()}};
    if (record.claim) json["claim"] = true;
    if (record.bd_seq) json["bd_seq"] = *record.bd_seq;
    return json.dump();
}

std::optional<core::redundancy::LeaderRecord> decode_leader_record(std::string_view payload) {
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
    return record;
}

}  // namespace eip2mqtt::app::redundancy
