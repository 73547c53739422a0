#pragma once
/// What a Write or Masked Write on UDP 7937 amounts to (docs/protocol.md §9.4): the tag writes
/// that give the exchange the bytes asked for, checked as an MQTT write is checked.

#include <optional>
#include <span>
#include <vector>

#include "eip2mqtt/core/command/command_status.hpp"
#include "eip2mqtt/core/command/data_pdus.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/result.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::core::command {

/// Why a write is refused: its status, and for `rejected` the write checks' reason (what an
/// MQTT write refused alike is counted and answered by).
struct WriteRefusal {
    CommandStatus status = CommandStatus::rejected;
    std::optional<write::WriteRejection> rejection;
};

/// The cells of `pdu` laid over `image` (the exchange's current data, plan.length bytes): every
/// bit written (each bit of a Write's bytes, each bit set in a Masked Write's mask) must lie
/// inside a writable tag (not_permitted otherwise); each writable tag with a bit written takes
/// its value from the image so written, and passes write::validate_write and the overlap check
/// (rejected otherwise, with the check's rejection). Cells are assumed inside the exchange. An
/// empty result: nothing written (a mask of zeros).
Result<std::vector<write::TagWrite>, WriteRefusal> plan_write(const plan::ExchangePlan& plan,
                                                              std::span<const std::byte> image,
                                                              const DataPdu& pdu, bool masked);

}  // namespace eip2mqtt::core::command
