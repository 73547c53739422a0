// docs/protocol.md §9.7. The token is SipHash-2-4 (Aumasson and Bernstein, 2012) of the address
// and the period, keyed with the responder's secret: a requester that learns its own tokens
// learns nothing of another address's.

#include "eip2mqtt/core/command/address_proof.hpp"

#include "core/command/detail/byte_io.hpp"
#include "core/command/detail/header_io.hpp"
#include "eip2mqtt/core/command/command_status.hpp"

namespace eip2mqtt::core::command {
namespace {

constexpr std::uint64_t rotl(std::uint64_t x, int b) { return (x << b) | (x >> (64 - b)); }

struct SipState {
    std::uint64_t v0, v1, v2, v3;

    void round() {
        v0 += v1;
        v1 = rotl(v1, 13);
        v1 ^= v0;
        v0 = rotl(v0, 32);
        v2 += v3;
        v3 = rotl(v3, 16);
        v3 ^= v2;
        v0 += v3;
        v3 = rotl(v3, 21);
        v3 ^= v0;
        v2 += v1;
        v1 = rotl(v1, 17);
        v1 ^= v2;
        v2 = rotl(v2, 32);
    }
    void absorb(std::uint64_t m) {
        v3 ^= m;
        round();
        round();
        v0 ^= m;
    }
};

// SipHash-2-4 of one 8-byte message word.
std::uint64_t siphash(const ProofKey& key, std::uint64_t message) {
    SipState s{key[0] ^ 0x736f6d6570736575ULL, key[1] ^ 0x646f72616e646f6dULL,
               key[0] ^ 0x6c7967656e657261ULL, key[1] ^ 0x7465646279746573ULL};
    s.absorb(message);
    s.absorb(std::uint64_t{8} << 56);  // the length byte, no tail
    s.v2 ^= 0xFF;
    for (int i = 0; i < 4; ++i) s.round();
    return s.v0 ^ s.v1 ^ s.v2 ^ s.v3;
}

std::int64_t period_of(MonoTime now) {
    return std::chrono::duration_cast<std::chrono::minutes>(now.time_since_epoch()).count() /
           token_period.count();
}

}  // namespace

std::uint32_t AddressProof::token_at(std::uint32_t address, std::int64_t period) const {
    const auto message = std::uint64_t{address} | static_cast<std::uint64_t>(period) << 32;
    return static_cast<std::uint32_t>(siphash(key_, message) & 0xFFFFFF);
}

std::uint32_t AddressProof::token(std::uint32_t address, MonoTime now) const {
    return token_at(address, period_of(now));
}

bool AddressProof::proves(const PduHeader& header, std::uint32_t address, MonoTime now) const {
    const auto carried = carried_token(header);
    const auto period = period_of(now);
    return carried == token_at(address, period) || carried == token_at(address, period - 1);
}

bool AddressProof::proves(std::span<const std::byte> pdu, std::uint32_t address,
                          MonoTime now) const {
    if (pdu.size() < header_size) return false;
    detail::ByteReader in(pdu);
    PduHeader header;
    header.flag = in.u8(1);
    header.request_id = in.u16(2);
    return proves(header, address, now);
}

std::uint32_t carried_token(const PduHeader& header) {
    return std::uint32_t{header.flag} << 16 | header.request_id;
}

void carry_token(std::span<std::byte> request, std::uint32_t token) {
    if (request.size() < header_size) return;
    request[1] = static_cast<std::byte>(token >> 16 & 0xFF);
    request[2] = static_cast<std::byte>(token & 0xFF);
    request[3] = static_cast<std::byte>(token >> 8 & 0xFF);
}

std::vector<std::byte> challenge(const PduHeader& request, std::size_t request_size,
                                 std::uint32_t token) {
    std::vector<std::byte> pdu;
    detail::ByteWriter out(pdu);
    const auto type = response_type_of(request.type).value_or(PduType::nak);
    detail::put_header(
        out, reply_header(request, type, static_cast<std::uint8_t>(CommandStatus::prove_address)));
    if (request_size >= challenge_size) out.u32(token & 0xFFFFFF);
    return detail::finish(std::move(pdu));
}

std::optional<std::uint32_t> challenge_token(std::span<const std::byte> response) {
    if (response.size() != challenge_size) return std::nullopt;
    detail::ByteReader in(response);
    if (in.u8(4) != protocol_version || in.u16(6) != challenge_size ||
        in.u8(5) != static_cast<std::uint8_t>(CommandStatus::prove_address)) {
        return std::nullopt;
    }
    const auto type = pdu_type_of(in.u8(0));
    if (!type || is_request(*type)) return std::nullopt;
    return in.u32(8) & 0xFFFFFF;
}

}  // namespace eip2mqtt::core::command
