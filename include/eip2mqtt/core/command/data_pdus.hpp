#pragma once
/// Read, Write and Masked Write (docs/protocol.md §9.4): a 32-byte fixed part naming the
/// exchange, then cells of (offset, length[, data][, mask]).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::command {

inline constexpr std::size_t data_fixed_size = 32;
inline constexpr std::size_t cell_head_size = 4;
/// Address type 0: offsets within the exchange, the only one eip2mqtt serves.
inline constexpr std::uint8_t address_type_exchange = 0;

/// `size` rounded up to a multiple of 4: data and masks are padded to 32 bits.
constexpr std::size_t padded(std::size_t size) { return (size + 3) / 4 * 4; }

/// One cell: `length` bytes from `offset` in the exchange's data. `data` is empty in a Read
/// request and in Write responses; `mask` is set only in a Masked Write request, where a 1 bit
/// means "this bit takes the data's value".
struct Cell {
    std::uint16_t offset = 0;
    std::uint16_t length = 0;
    std::vector<std::byte> data;
    std::vector<std::byte> mask;
    friend bool operator==(const Cell&, const Cell&) = default;
};

/// The fixed part and the cells of a Read, Write or Masked Write PDU; the header's type says
/// which, and whether it is a request or a response.
struct DataPdu {
    std::uint16_t signature = 0;  ///< major << 8 | minor; 0 = not checked
    std::uint8_t address_type = address_type_exchange;
    wire::ExchangeKey key;
    std::uint32_t time_s = 0;  ///< the image's sampling time in a response; 0 in requests
    std::uint32_t time_ns = 0;
    std::vector<Cell> cells;
    friend bool operator==(const DataPdu&, const DataPdu&) = default;
};

/// The size of a Read response carrying `cells` (each with `length` data bytes).
std::size_t read_response_size(const std::vector<Cell>& cells);

}  // namespace eip2mqtt::core::command
