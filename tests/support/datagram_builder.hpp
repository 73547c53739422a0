#pragma once
/// Builds EIP datagrams for tests, from hex or from header fields and tag values.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::test {

/// Bytes of a hex string (whitespace ignored).
std::vector<std::byte> from_hex(std::string_view hex);
std::string to_hex(const std::vector<std::byte>& bytes);

class DatagramBuilder {
public:
    DatagramBuilder(std::string_view producer_id, std::uint32_t exchange_id, std::size_t length);

    DatagramBuilder& request_id(std::uint16_t rid);
    DatagramBuilder& timestamp(std::uint32_t seconds, std::uint32_t nanoseconds);
    DatagramBuilder& signature(std::uint8_t major, std::uint8_t minor);
    DatagramBuilder& set(std::string_view address, core::plan::TagType type,
                         const core::plan::Value& value);
    /// Header + data.
    std::vector<std::byte> build() const;

    core::wire::Header& header() { return header_; }
    std::vector<std::byte>& data() { return data_; }

private:
    core::wire::Header header_;
    std::vector<std::byte> data_;
};

}  // namespace eip2mqtt::test
