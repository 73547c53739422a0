#pragma once
/// What follows each cell's offset and length in a Read, Write or Masked Write PDU (§9.4), the
/// same for the decoder and the encoder.

#include <cstdint>
#include <optional>

#include "eip2mqtt/core/command/pdu_header.hpp"

namespace eip2mqtt::core::command::detail {

struct CellShape {
    bool data = false;
    bool mask = false;
};

/// nullopt: the PDU has no cells at all.
constexpr std::optional<CellShape> cell_shape(PduType type, std::uint8_t status) {
    switch (type) {
        case PduType::read_request:
            return CellShape{};
        case PduType::write_request:
            return CellShape{true, false};
        case PduType::masked_write_request:
            return CellShape{true, true};
        // A Read response carries the data; one with an error status carries no cell.
        case PduType::read_response:
            if (status != 0) return std::nullopt;
            return CellShape{true, false};
        // Write responses are the fixed part alone; no other type is a data PDU.
        default:
            return std::nullopt;
    }
}

}  // namespace eip2mqtt::core::command::detail
