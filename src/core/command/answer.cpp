#include "eip2mqtt/core/command/answer.hpp"

#include <algorithm>

#include "eip2mqtt/core/command/encode.hpp"

namespace eip2mqtt::core::command {
namespace {

PduHeader response_to(const PduHeader& request, CommandStatus status = CommandStatus::success) {
    return reply_header(request, *response_type_of(request.type),
                        static_cast<std::uint8_t>(status));
}

std::uint16_t signature_of(const ExchangeView& view) { return view.plan->spec.signature.to_wire(); }

std::uint32_t period_of(const ExchangeView& view) {
    return static_cast<std::uint32_t>(view.plan->spec.period.count());
}

// docs/protocol.md §9.3: an unknown exchange gets the response of full size, its ids, and
// status unknown_exchange.
std::vector<std::byte> retrieve_config(const PduHeader& header, const RetrieveConfigRequest& body,
                                       std::span<const ExchangeView> exchanges) {
    const auto* view = find_exchange(exchanges, body.key);
    if (view == nullptr) {
        ExchangeConfig unknown;
        unknown.key = body.key;
        unknown.destination_type = DestinationType::none;
        unknown.port = 0;
        unknown.state = static_cast<ExchangeState>(0);
        unknown.mode = static_cast<ExchangeMode>(0);
        return encode(response_to(header, CommandStatus::unknown_exchange), unknown);
    }
    ExchangeConfig config;
    config.key = body.key;
    config.period_ms = period_of(*view);
    config.destination_type = view->destination_type;
    config.destination = view->destination;
    config.state = view->state;
    config.length = view->plan->length;
    config.port = view->port;
    config.signature = signature_of(*view);
    config.mode = view->mode;
    return encode(response_to(header), config);
}

std::vector<std::byte> summary(const PduHeader& header, const SummaryRequest& body,
                               const NodeInfo& node, std::span<const ExchangeView> exchanges) {
    SummaryPage page;
    page.index = body.index;
    page.producer_id = node.producer_id;
    page.total_cells = static_cast<std::uint16_t>(std::min<std::size_t>(exchanges.size(), 0xFFFF));
    for (std::size_t i = body.index; i < exchanges.size() && page.cells.size() < max_summary_cells;
         ++i) {
        const auto& view = exchanges[i];
        page.cells.push_back({view.plan->key(), view.mode, view.state, period_of(view)});
    }
    return encode(response_to(header), page);
}

std::vector<std::byte> capabilities(const PduHeader& header, const NodeInfo& node,
                                    std::span<const ExchangeView> exchanges) {
    Capabilities body;
    body.producer_id = node.producer_id;
    body.max_exchanges = static_cast<std::uint32_t>(exchanges.size());
    body.capabilities = capability::read;
    for (const auto& view : exchanges) {
        body.capabilities |=
            view.mode == ExchangeMode::produced ? capability::produces : capability::consumes;
    }
    if (node.writes) body.capabilities |= capability::write | capability::masked_write;
    body.identification = node.identification;
    return encode(response_to(header), body);
}

std::vector<std::byte> statistics(const PduHeader& header, const StatisticsRequest& body,
                                  std::span<const ExchangeView> exchanges) {
    const auto* view = find_exchange(exchanges, body.key);
    ExchangeStatistics out;
    out.key = body.key;
    if (view == nullptr) {
        out.state = static_cast<ExchangeState>(0);
        return encode(response_to(header, CommandStatus::unknown_exchange), out);
    }
    out.config_time_s = view->config_time_s;
    out.due_time_ms = view->due_time_ms;
    out.state = view->state;
    out.length = view->plan->length;
    out.messages = view->messages;
    out.missed = view->missed;
    out.refresh_errors = view->refresh_errors;
    return encode(response_to(header), out);
}

}  // namespace

const ExchangeView* find_exchange(std::span<const ExchangeView> exchanges,
                                  const wire::ExchangeKey& key) {
    const auto found =
        std::find_if(exchanges.begin(), exchanges.end(),
                     [&](const ExchangeView& view) { return view.plan->key() == key; });
    return found == exchanges.end() ? nullptr : &*found;
}

Answer answer(const Request& request, const NodeInfo& node,
              std::span<const ExchangeView> exchanges) {
    const auto& header = request.header;
    return std::visit(
        [&](const auto& body) -> Answer {
            using Body = std::decay_t<decltype(body)>;
            if constexpr (std::is_same_v<Body, RetrieveConfigRequest>) {
                return retrieve_config(header, body, exchanges);
            } else if constexpr (std::is_same_v<Body, SummaryRequest>) {
                return summary(header, body, node, exchanges);
            } else if constexpr (std::is_same_v<Body, CapabilitiesRequest>) {
                return capabilities(header, node, exchanges);
            } else if constexpr (std::is_same_v<Body, StatisticsRequest>) {
                return statistics(header, body, exchanges);
            } else {
                return answer_data(header, body, node, exchanges);
            }
        },
        request.body);
}

std::vector<std::byte> write_response(const Request& request, CommandStatus status,
                                      std::uint32_t time_s, std::uint32_t time_ns) {
    const auto& asked = std::get<DataPdu>(request.body);
    DataPdu pdu;
    pdu.signature = asked.signature;
    pdu.address_type = asked.address_type;
    pdu.key = asked.key;
    pdu.time_s = time_s;
    pdu.time_ns = time_ns;
    return encode(response_to(request.header, status), pdu);
}

}  // namespace eip2mqtt::core::command
