#pragma once
/// How a responder answers a request it decoded (docs/protocol.md §9.3-9.5), from views of its
/// exchanges taken when the request came. Pure: the caller sends the bytes, and stages the
/// writes a Write or Masked Write asks for.

#include <cstddef>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "eip2mqtt/core/command/command_status.hpp"
#include "eip2mqtt/core/command/decode.hpp"
#include "eip2mqtt/core/command/exchange_view.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::core::command {

/// The validated tag writes of a Write or Masked Write, for the exchange of `exchange` (the
/// ExchangeView's plan), applied whole in one datagram. The response goes once they are
/// (write_response).
struct StageWrites {
    const plan::ExchangePlan* exchange = nullptr;
    std::vector<write::TagWrite> writes;
    /// Set when the write checks refused a value: nothing to apply, but the refusal goes where
    /// an MQTT write's does, to be counted by its reason and answered `rejected`.
    std::optional<write::WriteRejection> rejection;
};

/// The bytes to send back, or writes to stage before answering.
using Answer = std::variant<std::vector<std::byte>, StageWrites>;

/// The answer to `request`. Every response is built here, an error status included (an
/// unknown exchange, a Read of data not there yet, a write refused); a write that passes every
/// check, or that only the write checks refuse, becomes StageWrites.
Answer answer(const Request& request, const NodeInfo& node,
              std::span<const ExchangeView> exchanges);

/// The Write or Masked Write response to `request` with `status`, the data's time `time_s`.
std::vector<std::byte> write_response(const Request& request, CommandStatus status,
                                      std::uint32_t time_s = 0, std::uint32_t time_ns = 0);

/// The answer to a Read, Write or Masked Write (answer_data.cpp).
Answer answer_data(const PduHeader& header, const DataPdu& pdu, const NodeInfo& node,
                   std::span<const ExchangeView> exchanges);

/// The exchange `key` names, or nullptr.
const ExchangeView* find_exchange(std::span<const ExchangeView> exchanges,
                                  const wire::ExchangeKey& key);

}  // namespace eip2mqtt::core::command
