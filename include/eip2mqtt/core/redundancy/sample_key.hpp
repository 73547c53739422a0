#pragma once
/// What names a consumed exchange's sample alike on both units of a pair
/// (docs/redundancy.md): both receive the same datagrams, so the datagram's own header, its request
/// id and its producer's timestamp, is the same on both, where the time each unit received it, and
/// so the timestamp it publishes with the receive-time clock, is not. The pair's watermark (the
/// newest sample the leader had acknowledged) and the standby's window of samples are told
/// apart in these terms (docs/architecture.md, "The watermark").

#include <cstdint>
#include <tuple>

namespace eip2mqtt::core::redundancy {

struct SampleKey {
    std::uint16_t request_id = 0;
    std::uint32_t time_s = 0;  ///< the producer's timestamp; 0: it sends none
    std::uint32_t time_ns = 0;
    /// 0: the datagram's own sample; n: the n-th change of quality reported after it (the
    /// exchange found stale, or in mismatch), which carries no header of its own.
    std::uint8_t change = 0;

    friend bool operator==(const SampleKey&, const SampleKey&) = default;
};

/// Whether sample `a` came after sample `b` of the same exchange, by the consumer's own rule
/// (docs/protocol.md §4 rule 6): a request id 1 to 32767 ahead is newer, one behind is older
/// unless the producer's timestamp moved forward (both non-zero: the producer restarted, its
/// request ids with it). The same datagram orders by its changes of quality.
constexpr bool comes_after(const SampleKey& a, const SampleKey& b) {
    if (a.request_id == b.request_id && a.time_s == b.time_s && a.time_ns == b.time_ns) {
        return a.change > b.change;
    }
    const auto ahead = static_cast<std::uint16_t>(a.request_id - b.request_id);
    if (ahead != 0 && ahead < 32768) return true;
    if (a.time_s == 0 || b.time_s == 0) return false;
    return std::tie(a.time_s, a.time_ns) > std::tie(b.time_s, b.time_ns);
}

}  // namespace eip2mqtt::core::redundancy
