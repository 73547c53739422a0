#include "eip2mqtt/core/command/response_match.hpp"

#include <algorithm>

namespace eip2mqtt::core::command {
namespace {

// The exchange a request names, if its type names one.
std::optional<wire::ExchangeKey> key_of(const RequestBody& body) {
    if (const auto* r = std::get_if<RetrieveConfigRequest>(&body)) return r->key;
    if (const auto* s = std::get_if<StatisticsRequest>(&body)) return s->key;
    if (const auto* d = std::get_if<DataPdu>(&body)) return d->key;
    return std::nullopt;
}

bool nak_matches(const Request& request, std::span<const std::byte> bytes, const CommandNak& nak) {
    const auto echoed = bytes.first(std::min(bytes.size(), nak_echo_size));
    if (nak.offending.size() < echoed.size() ||
        !std::equal(echoed.begin(), echoed.end(), nak.offending.begin())) {
        return false;
    }
    const auto key = key_of(request.body);
    return !key || nak.key == *key;
}

bool body_matches(const RequestBody& asked, const ResponseBody& body) {
    if (const auto* config = std::get_if<ExchangeConfig>(&body))
        return config->key == key_of(asked);
    if (const auto* stats = std::get_if<ExchangeStatistics>(&body)) {
        return stats->key == key_of(asked);
    }
    if (const auto* data = std::get_if<DataPdu>(&body)) return data->key == key_of(asked);
    if (const auto* page = std::get_if<SummaryPage>(&body)) {
        const auto* summary = std::get_if<SummaryRequest>(&asked);
        return summary != nullptr && summary->index == page->index;
    }
    // Capabilities: the node's own producer id, whatever was asked.
    return std::holds_alternative<Capabilities>(body);
}

}  // namespace

bool answers_request(const Request& request, std::span<const std::byte> request_bytes,
                     const Response& response) {
    const auto& asked = request.header;
    const auto& got = response.header;
    if (got.flag != asked.flag || got.request_id != asked.request_id) return false;
    if (const auto* nak = std::get_if<CommandNak>(&response.body)) {
        return got.type == PduType::nak && nak_matches(request, request_bytes, *nak);
    }
    return got.type == response_type_of(asked.type) && body_matches(request.body, response.body);
}

}  // namespace eip2mqtt::core::command
