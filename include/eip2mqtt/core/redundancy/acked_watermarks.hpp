#pragma once
/// The leader's side of a pair's watermark (docs/redundancy.md): for each consumed exchange,
/// the newest of its samples whose publication the broker acknowledged, which the leader's
/// renewals carry, so that a standby taking over publishes on `_history` only what came after.
/// "Newest" is the order of publication, whatever order the acknowledgements come in (a
/// reconnect sends again what was in flight). Pure: the caller hands each publication's token
/// to the client and each acknowledged token back.
///
/// Threading: one thread (the loop).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/core/redundancy/sample_key.hpp"

namespace eip2mqtt::core::redundancy {

class AckedWatermarks {
public:
    /// Set in every token handed out, never in a journal entry's id (store and forward's tokens
    /// on the same connection) nor in the Sparkplug node's own (bit 63, another connection).
    static constexpr std::uint64_t token_bit = std::uint64_t{1} << 62;
    static constexpr bool owns(std::uint64_t token) { return (token & token_bit) != 0; }

    /// `remembered`: how many publications awaiting acknowledgement are remembered, rounded up
    /// to a power of two; the acknowledgement of an older one is ignored (the client holds far
    /// fewer: its `_values` lane and its window in flight).
    explicit AckedWatermarks(std::size_t remembered = 4096);

    /// A publication of `key`, a sample of `exchange` (a number the caller gives each running
    /// exchange), goes to the broker: the token it carries, never 0.
    std::uint64_t published(std::uint32_t exchange, const SampleKey& key);
    /// The broker acknowledged the publication that carried `token`: the watermark of its
    /// exchange moves to its sample, unless a later publication of it was acknowledged already.
    void acknowledged(std::uint64_t token);

    /// The watermark of `exchange` until its first acknowledgement: the one the unit that led
    /// before said last (a new leader's renewals go on saying it).
    void start_at(std::uint32_t exchange, const SampleKey& key);
    /// An exchange that stopped (a reload).
    void forget(std::uint32_t exchange);
    /// Every watermark and every publication awaiting acknowledgement (stepping down).
    void clear();

    std::optional<SampleKey> watermark(std::uint32_t exchange) const;

private:
    struct Publication {
        std::uint64_t serial = 0;  ///< 0: none
        std::uint32_t exchange = 0;
        SampleKey key;
    };
    struct Mark {
        std::uint64_t serial = 0;  ///< of the publication acknowledged; 0: start_at's
        SampleKey key;
    };

    std::vector<Publication> awaiting_;  ///< by serial, modulo its size
    std::uint64_t last_serial_ = 0;
    std::unordered_map<std::uint32_t, Mark> marks_;
};

}  // namespace eip2mqtt::core::redundancy
