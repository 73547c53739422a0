// Read, Write and Masked Write answered (docs/protocol.md §9.4, §9.5).

#include <algorithm>

#include "eip2mqtt/core/command/answer.hpp"
#include "eip2mqtt/core/command/encode.hpp"
#include "eip2mqtt/core/command/write_plan.hpp"

namespace eip2mqtt::core::command {
namespace {

// The fixed part alone, with the request's exchange and `status`.
std::vector<std::byte> refuse(const PduHeader& header, const DataPdu& asked, CommandStatus status) {
    DataPdu pdu;
    pdu.signature = asked.signature;
    pdu.address_type = asked.address_type;
    pdu.key = asked.key;
    return encode(
        reply_header(header, *response_type_of(header.type), static_cast<std::uint8_t>(status)),
        pdu);
}

// Why the exchange cannot serve the cells at all, whatever the operation.
std::optional<CommandStatus> cells_problem(const DataPdu& pdu, const ExchangeView& view) {
    if (pdu.address_type != address_type_exchange) return CommandStatus::unsupported_address;
    if (pdu.signature != 0 && pdu.signature != view.plan->spec.signature.to_wire()) {
        return CommandStatus::signature_mismatch;
    }
    const bool inside = std::all_of(pdu.cells.begin(), pdu.cells.end(), [&](const Cell& cell) {
        return std::size_t{cell.offset} + cell.length <= view.plan->length;
    });
    if (!inside) return CommandStatus::out_of_range;
    return std::nullopt;
}

Answer read(const PduHeader& header, const DataPdu& asked, const ExchangeView& view) {
    if (view.image.size() < view.plan->length) return refuse(header, asked, CommandStatus::no_data);
    if (read_response_size(asked.cells) > max_pdu_size) {
        return refuse(header, asked, CommandStatus::out_of_range);
    }
    DataPdu pdu;
    pdu.signature = asked.signature;
    pdu.address_type = asked.address_type;
    pdu.key = asked.key;
    pdu.time_s = view.time_s;
    pdu.time_ns = view.time_ns;
    for (const auto& cell : asked.cells) {
        const auto bytes = view.image.subspan(cell.offset, cell.length);
        pdu.cells.push_back({cell.offset, cell.length, {bytes.begin(), bytes.end()}, {}});
    }
    return encode(reply_header(header, PduType::read_response), pdu);
}

}  // namespace

Answer answer_data(const PduHeader& header, const DataPdu& pdu, const NodeInfo& node,
                   std::span<const ExchangeView> exchanges) {
    const auto* view = find_exchange(exchanges, pdu.key);
    if (view == nullptr) return refuse(header, pdu, CommandStatus::unknown_exchange);
    const bool reading = header.type == PduType::read_request;
    // Writes off, or a consumed exchange: refused before anything else is looked at.
    if (!reading && (!node.writes || !view->writable)) {
        return refuse(header, pdu, CommandStatus::not_permitted);
    }
    if (const auto problem = cells_problem(pdu, *view)) return refuse(header, pdu, *problem);
    if (reading) return read(header, pdu, *view);
    auto writes =
        plan_write(*view->plan, view->image, pdu, header.type == PduType::masked_write_request);
    if (!writes) {
        auto refusal = writes.error();
        if (refusal.rejection) return StageWrites{view->plan, {}, std::move(refusal.rejection)};
        return refuse(header, pdu, refusal.status);
    }
    if (writes->empty()) return refuse(header, pdu, CommandStatus::success);
    return StageWrites{view->plan, std::move(writes).value()};
}

}  // namespace eip2mqtt::core::command
