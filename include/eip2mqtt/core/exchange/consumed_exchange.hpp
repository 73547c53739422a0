#pragma once
/// The consumer state of one exchange: signature, length and sequence rules, the update timeout
/// and the counters of `_status` (docs/protocol.md §4 rules 4-8). Pure: time is passed in.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/exchange/consume_counters.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"

namespace eip2mqtt::core::exchange {

enum class ConsumeState : std::uint8_t {
    waiting,             ///< nothing accepted yet
    ok,                  ///< receiving on time
    stale,               ///< no accepted sample within the timeout
    signature_mismatch,  ///< the last datagram's signature is incompatible
    length_mismatch,     ///< the last datagram's length differs from the configured one
};

inline constexpr auto consume_state_names =
    enum_names<ConsumeState>("waiting", "ok", "stale", "signature_mismatch", "length_mismatch");

constexpr std::string_view to_string(ConsumeState state) {
    return consume_state_names.name_of(state);
}

/// What became of one datagram.
struct ConsumeOutcome {
    std::optional<wire::DropReason> dropped;  ///< nullopt: accepted
    bool state_changed = false;               ///< state() differs from before the datagram

    bool accepted() const { return !dropped.has_value(); }
};

class ConsumedExchange {
public:
    /// `length` and `timeout` come from the plan; `signature` is the configured one.
    explicit ConsumedExchange(const plan::ExchangePlan& plan);

    /// Whether a datagram of this exchange that came from `address` (IPv4, host order) may be
    /// applied: any address when the exchange has no `source`. A refusal is counted; the
    /// caller drops the datagram (DropReason::wrong_source).
    bool accepts_source(std::uint32_t address);

    /// Applies rules 4-7 to a datagram of this exchange (the caller matched the key).
    /// On acceptance, image() holds the first `length` data bytes.
    ConsumeOutcome on_datagram(const wire::Datagram& datagram, MonoTime now);

    /// Applies rule 8; returns true when the exchange has just become stale. Only `ok` and the
    /// mismatch states time out (after `timeout` without an accepted sample, respectively
    /// without any datagram); `waiting` never does, and `stale` is reported once.
    bool on_tick(MonoTime now);

    /// When on_tick next has something to do; nullopt when the timeout is disabled or the
    /// exchange is not waiting for a sample (states `waiting` and `stale`).
    std::optional<MonoTime> next_deadline() const;

    ConsumeState state() const { return state_; }
    const ConsumeCounters& counters() const { return counters_; }
    /// A publication of one of its scaled tags carried a value beyond the scale's raw range.
    void count_beyond_raw_range() { ++counters_.beyond_raw_range; }
    /// The last accepted data; empty until a sample was accepted.
    std::span<const std::byte> image() const;
    bool has_image() const { return has_image_; }
    /// Header of the last accepted datagram.
    const wire::Header& last_header() const { return last_header_; }
    /// Monotonic time of the last accepted datagram.
    std::optional<MonoTime> last_accepted() const { return last_accepted_; }

private:
    /// Rules 4 and 5: the reason to drop a datagram (signed `received`) of another signature
    /// or length.
    std::optional<wire::DropReason> check_form(const wire::Datagram& datagram,
                                               wire::Signature received, MonoTime now);
    /// Rule 6: the reason to drop a datagram that is no new sample.
    std::optional<wire::DropReason> check_sequence(const wire::Header& header,
                                                   wire::Signature received);
    /// A mismatch of signature or length: the exchange turns `state`, and the sequence is
    /// unknown until the next accepted datagram resynchronises it.
    wire::DropReason mismatch(ConsumeState state, wire::DropReason reason, MonoTime now);
    /// Rule 7: takes the datagram's data as the image.
    void accept(const wire::Datagram& datagram, MonoTime now);

    std::size_t length_;
    std::chrono::milliseconds timeout_;
    wire::Signature signature_;
    std::optional<std::uint32_t> source_;
    ConsumeState state_ = ConsumeState::waiting;
    bool resync_ = true;  ///< the next datagram resynchronises the sequence without counting
    bool has_image_ = false;
    std::vector<std::byte> image_;
    wire::Header last_header_;
    std::optional<MonoTime> last_accepted_;
    /// Where the update timeout counts from: the last accepted sample in `ok`, the last
    /// datagram in a mismatch state (so a producer that keeps sending incompatible data stays
    /// `bad`, and one that falls silent becomes `stale`).
    MonoTime timer_start_{};
    ConsumeCounters counters_;
};

}  // namespace eip2mqtt::core::exchange
