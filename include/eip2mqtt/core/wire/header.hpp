#pragma once
/// The 32-byte header of an EIP data production PDU (docs/protocol.md §2).

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace eip2mqtt::core::wire {

inline constexpr std::size_t header_size = 32;
inline constexpr std::size_t max_data_size = 1400;
inline constexpr std::size_t max_datagram_size = header_size + max_data_size;
inline constexpr std::uint8_t pdu_type_data = 0x0D;
inline constexpr std::uint8_t pdu_version = 0x01;
inline constexpr std::uint16_t default_port = 18246;

/// A Producer ID: 4 bytes sent in dotted order. Held as a u32 whose most significant byte is
/// the first dotted octet (192.168.1.1 == 0xC0A80101), which is also how it is compared.
struct ProducerId {
    std::uint32_t value = 0;
    friend bool operator==(const ProducerId&, const ProducerId&) = default;
    friend auto operator<=>(const ProducerId&, const ProducerId&) = default;
};

/// Parses `a.b.c.d`, or GE's "decimal" form: a plain integer that is the 4 wire bytes read as a
/// little-endian u32 (172.23.21.176 == 2954172332).
std::optional<ProducerId> parse_producer_id(std::string_view text);
std::string to_string(ProducerId id);

/// Configuration signature: low 16 bits of the field; major = byte 25, minor = byte 24.
struct Signature {
    std::uint8_t major = 0;
    std::uint8_t minor = 0;

    bool is_set() const { return major != 0 || minor != 0; }
    std::uint16_t to_wire() const { return static_cast<std::uint16_t>(major << 8 | minor); }
    static Signature from_wire(std::uint32_t field) {
        return {static_cast<std::uint8_t>(field >> 8 & 0xFF),
                static_cast<std::uint8_t>(field & 0xFF)};
    }
    friend bool operator==(const Signature&, const Signature&) = default;
};

/// Parses `major.minor` (each 0..255) or `major` (minor 0).
std::optional<Signature> parse_signature(std::string_view text);
std::string to_string(Signature signature);

/// The pair that identifies an exchange on the wire (never the source address).
struct ExchangeKey {
    ProducerId producer_id;
    std::uint32_t exchange_id = 0;
    friend bool operator==(const ExchangeKey&, const ExchangeKey&) = default;
    friend auto operator<=>(const ExchangeKey&, const ExchangeKey&) = default;
};

struct ExchangeKeyHash {
    std::size_t operator()(const ExchangeKey& key) const noexcept {
        return std::hash<std::uint64_t>{}(std::uint64_t{key.producer_id.value} << 32 |
                                          key.exchange_id);
    }
};

/// Every header field, decoded. Multi-byte integers are little-endian on the wire.
struct Header {
    std::uint8_t pdu_type = pdu_type_data;
    std::uint8_t pdu_version = wire::pdu_version;
    std::uint16_t request_id = 0;
    ProducerId producer_id;
    std::uint32_t exchange_id = 0;
    std::uint32_t time_s = 0;     ///< seconds since 1970 UTC; 0 means "no timestamp"
    std::uint32_t time_ns = 0;    ///< 0..999 999 999
    std::uint32_t status = 0;     ///< recorded, never rejected on
    std::uint32_t signature = 0;  ///< raw field; see Signature::from_wire
    std::uint32_t reserved = 0;

    ExchangeKey key() const { return {producer_id, exchange_id}; }
    bool has_timestamp() const { return time_s != 0; }
};

}  // namespace eip2mqtt::core::wire
