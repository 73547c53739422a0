#include "eip2mqtt/core/exchange/consumed_exchange.hpp"

#include <cstddef>
#include <utility>

namespace eip2mqtt::core::exchange {
namespace {

// docs/protocol.md §4 rule 4: consume only when both are set, the majors are equal and the
// received minor is not older than the configured one; an unset side disables the check.
bool compatible(wire::Signature configured, wire::Signature received) {
    if (!configured.is_set() || !received.is_set()) return true;
    return received.major == configured.major && received.minor >= configured.minor;
}

// §4 rule 5: a compatible newer minor may append data after the configured bytes.
bool may_append(wire::Signature configured, wire::Signature received) {
    return configured.is_set() && received.is_set() && received.minor > configured.minor;
}

/// Whether the producer's time moved forward from `last` to `next`, both being set: a datagram
/// whose request id looks old then comes from a producer that restarted, not from the past.
bool time_moved_forward(const wire::Header& last, const wire::Header& next) {
    if (!last.has_timestamp() || !next.has_timestamp()) return false;
    return std::pair(next.time_s, next.time_ns) > std::pair(last.time_s, last.time_ns);
}

bool times_out(ConsumeState state) {
    return state == ConsumeState::ok || state == ConsumeState::signature_mismatch ||
           state == ConsumeState::length_mismatch;
}

}  // namespace

ConsumedExchange::ConsumedExchange(const plan::ExchangePlan& plan)
    : length_(plan.length),
      timeout_(plan.timeout),
      signature_(plan.spec.signature),
      source_(plan.spec.source) {
    image_.reserve(length_);
}

bool ConsumedExchange::accepts_source(std::uint32_t address) {
    if (!source_ || *source_ == address) return true;
    ++counters_.wrong_source;
    return false;
}

// The steps of on_datagram, inline: the data path pays no call for them.
inline std::optional<wire::DropReason> ConsumedExchange::check_form(const wire::Datagram& datagram,
                                                                    wire::Signature received,
                                                                    MonoTime now) {
    // §4 rule 4.
    if (!compatible(signature_, received)) {
        ++counters_.signature_mismatches;
        return mismatch(ConsumeState::signature_mismatch, wire::DropReason::signature_mismatch,
                        now);
    }
    // §4 rule 5.
    const std::size_t size = datagram.data.size();
    if (size == 0) {
        ++counters_.no_data;
        return wire::DropReason::no_data;
    }
    if (size != length_ && !(size > length_ && may_append(signature_, received))) {
        ++counters_.length_mismatches;
        return mismatch(ConsumeState::length_mismatch, wire::DropReason::length_mismatch, now);
    }
    return std::nullopt;
}

inline wire::DropReason ConsumedExchange::mismatch(ConsumeState state, wire::DropReason reason,
                                                   MonoTime now) {
    state_ = state;
    resync_ = true;
    timer_start_ = now;
    return reason;
}

inline std::optional<wire::DropReason> ConsumedExchange::check_sequence(const wire::Header& header,
                                                                        wire::Signature received) {
    // §4 rule 6: a new signature resynchronises, as do start-up, timeout and mismatches.
    if (has_image_ && wire::Signature::from_wire(last_header_.signature) != received) {
        resync_ = true;
    }
    if (resync_) return std::nullopt;
    const auto d = static_cast<std::uint16_t>(header.request_id - last_header_.request_id);
    if (d == 0) {
        // Proves the producer alive, but is no new sample: the update timer keeps running.
        ++counters_.duplicates;
        return wire::DropReason::duplicate;
    }
    if (d >= 32768) {
        // §4 rule 6: late or out of order, unless the producer restarted: its request ids
        // start again while its clock goes on. Resynchronise at once, counting no missed
        // datagrams across the restart (there were none).
        if (!time_moved_forward(last_header_, header)) {
            ++counters_.out_of_order;
            return wire::DropReason::out_of_order;
        }
        ++counters_.restarts;
    } else {
        counters_.missed += d - 1U;
    }
    return std::nullopt;
}

inline void ConsumedExchange::accept(const wire::Datagram& datagram, MonoTime now) {
    // §4 rule 7.
    image_.assign(datagram.data.begin(),
                  datagram.data.begin() + static_cast<std::ptrdiff_t>(length_));
    has_image_ = true;
    last_header_ = datagram.header;
    last_accepted_ = now;
    timer_start_ = now;
    resync_ = false;
    state_ = ConsumeState::ok;
    ++counters_.accepted;
}

ConsumeOutcome ConsumedExchange::on_datagram(const wire::Datagram& datagram, MonoTime now) {
    ++counters_.received;
    const ConsumeState before = state_;
    const auto received = wire::Signature::from_wire(datagram.header.signature);
    if (const auto reason = check_form(datagram, received, now)) {
        return ConsumeOutcome{*reason, state_ != before};
    }
    if (const auto reason = check_sequence(datagram.header, received)) {
        return ConsumeOutcome{*reason, state_ != before};
    }
    accept(datagram, now);
    return ConsumeOutcome{std::nullopt, state_ != before};
}

bool ConsumedExchange::on_tick(MonoTime now) {
    // §4 rule 8.
    const auto deadline = next_deadline();
    if (!deadline || now < *deadline) return false;
    state_ = ConsumeState::stale;
    resync_ = true;
    ++counters_.timeouts;
    return true;
}

std::optional<MonoTime> ConsumedExchange::next_deadline() const {
    if (timeout_.count() <= 0 || !times_out(state_)) return std::nullopt;
    return timer_start_ + timeout_;
}

std::span<const std::byte> ConsumedExchange::image() const {
    if (!has_image_) return {};
    return image_;
}

}  // namespace eip2mqtt::core::exchange
