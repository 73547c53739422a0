#pragma once
/// Proof that a requester receives what is sent to the address it asks from (docs/protocol.md
/// §9.7): a token the responder derives from the requester's IPv4 address with a secret key,
/// which the requester carries back in its message flag and request id (bytes 1-3, 24 bits).
/// Whoever forges another's source address never sees the answers to it, so cannot carry that
/// address's token: a responder that answers an unproven requester with no more bytes than it
/// asked with reflects nothing larger, and takes no write from it. Pure: key and time are
/// passed in.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "eip2mqtt/core/command/pdu_header.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::command {

/// A challenge: the header, then the token (u32, little-endian; its low 24 bits are used).
inline constexpr std::size_t challenge_size = 12;
/// A token is valid during its period and the next one.
inline constexpr std::chrono::minutes token_period{5};

/// The responder's secret: 128 random bits chosen at start.
using ProofKey = std::array<std::uint64_t, 2>;

class AddressProof {
public:
    explicit AddressProof(ProofKey key) : key_(key) {}

    /// The token of `address` (host order) at `now`: 24 bits.
    std::uint32_t token(std::uint32_t address, MonoTime now) const;
    /// Whether `header` carries the token of `address`, this period's or the previous one's.
    bool proves(const PduHeader& header, std::uint32_t address, MonoTime now) const;
    /// The same for a PDU as received (its bytes 1-3); false below the 8-byte header.
    bool proves(std::span<const std::byte> pdu, std::uint32_t address, MonoTime now) const;

private:
    std::uint32_t token_at(std::uint32_t address, std::int64_t period) const;

    ProofKey key_;
};

/// The token a request carries: message flag << 16 | request id.
std::uint32_t carried_token(const PduHeader& header);
/// Writes `token` into an encoded request's flag and request id (bytes 1-3).
void carry_token(std::span<std::byte> request, std::uint32_t token);

/// The answer to an unproven request of `request_size` bytes whose response would be larger:
/// the response type, the request's flag and id, status prove_address, and the token at 8;
/// the header alone when the request had fewer than 12 bytes. Never larger than the request.
std::vector<std::byte> challenge(const PduHeader& request, std::size_t request_size,
                                 std::uint32_t token);

/// The token of a challenge (a response of 12 bytes with status prove_address), or nullopt.
std::optional<std::uint32_t> challenge_token(std::span<const std::byte> response);

}  // namespace eip2mqtt::core::command
