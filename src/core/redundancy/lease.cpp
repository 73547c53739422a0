#include "eip2mqtt/core/redundancy/lease.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

namespace eip2mqtt::core::redundancy {
namespace {

std::uint64_t beat_of(MonoTime sent_at) {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(sent_at.time_since_epoch()).count());
}

}  // namespace

Lease::Lease(LeaseSettings settings, MonoTime start)
    : settings_(std::move(settings)), last_heard_(start) {}

bool Lease::outranks(const LeaderRecord& record) const {
    return std::tie(record.priority, record.id) > std::tie(settings_.priority, settings_.id);
}

bool Lease::gives_way(const LeaderRecord& record) const {
    switch (state_) {
        case State::standby:
            return true;
        case State::claiming:
            return !record.claim || outranks(record);
        case State::leader:
            // A renewal of the leader its claim named, after what it named: the claim was stale.
            return !record.claim && (outranks(record) || renews_after(record, named_));
    }
    return false;
}

bool Lease::renews_after(const LeaderRecord& record, const std::optional<LeaderMark>& mark) {
    return mark && !record.claim && record.id == mark->id && record.epoch >= mark->epoch &&
           record.beat > mark->beat;
}

bool Lease::stale(const LeaderRecord& claim) const {
    const auto newest = beat_of(last_acknowledged_.value_or(claimed_at_));
    return !claim.heard || claim.heard->id != settings_.id || claim.heard->epoch != epoch_ ||
           claim.heard->beat < newest;
}

LeaderRecord Lease::own_record() const {
    LeaderRecord record{settings_.id, epoch_, settings_.priority, state_ == State::claiming};
    record.beat = beat_of(last_sent_);
    if (record.claim) record.heard = named_;
    return record;
}

void Lease::follow(const LeaderRecord& record, MonoTime now) {
    epoch_ = std::max(epoch_, record.epoch);
    leader_id_ = record.id;
    heard_ = LeaderMark{record.id, record.epoch, record.beat};
    stand_by(now);
}

void Lease::on_connection(bool up, MonoTime now) {
    if (up && !connected_) {
        // What was queued went with the old connection: no claim of its is on its way.
        unanswered_claim_.reset();
        path_back_ = false;
        if (state_ == State::standby) last_heard_ = now;
    }
    connected_ = up;
}

void Lease::stand_by(MonoTime now) {
    state_ = State::standby;
    last_heard_ = now;
    last_acknowledged_.reset();
    reassert_ = false;
}

bool Lease::on_record(const std::optional<LeaderRecord>& record, MonoTime now) {
    // An empty record (a will) says nothing the time since the last record does not.
    if (!record) return false;
    if (record->id == settings_.id) {
        // Our claim heard back: what the broker had queued for this unit before it took the
        // claim came first (a subscriber's messages keep their order; an acknowledgement may
        // overtake them).
        if (state_ == State::claiming && record->claim && record->epoch == epoch_ &&
            record->beat >= beat_of(claimed_at_)) {
            echoed_ = true;
        }
        // Our own, or one from before a restart: its epoch is spent either way.
        epoch_ = std::max(epoch_, record->epoch);
        return false;
    }
    if (record->claim && state_ == State::leader && !fenced(now) && stale(*record)) {
        // Made while its claimant could not hear this leader: renewed over at once, under the
        // claim's epoch if higher, so that the claimant gives way to a renewal of its own.
        if (record->epoch >= epoch_) reassert_ = true;
        epoch_ = std::max(epoch_, record->epoch);
        return false;
    }
    const bool newer = record->epoch > epoch_;
    const bool same_and_gives_way = record->epoch == epoch_ && gives_way(*record);
    // The leader it follows renews still: whatever its own failed claim raised its epoch to.
    // Claiming, a renewal after the one its claim named, which the broker took before the
    // claim (it comes before the claim heard back): the claim was made without hearing it.
    // One the broker took after the claim is a leader's that finds the claim in its way.
    const bool still_heard =
        (state_ == State::standby && renews_after(*record, heard_)) ||
        (state_ == State::claiming && !echoed_ && renews_after(*record, named_));
    if (!newer && !same_and_gives_way && !still_heard) return false;
    follow(*record, now);
    return true;
}

void Lease::on_acknowledged(MonoTime sent_at) {
    if (unanswered_claim_ && sent_at >= *unanswered_claim_) {
        unanswered_claim_.reset();
        path_back_ = true;
    }
    if (state_ == State::standby || sent_at < claimed_at_) return;
    if (!last_acknowledged_ || sent_at > *last_acknowledged_) last_acknowledged_ = sent_at;
}

bool Lease::fenced(MonoTime now) const {
    if (state_ == State::standby) return true;
    const auto since = last_acknowledged_.value_or(claimed_at_);
    return now - since >= fence_after();
}

std::optional<MonoTime> Lease::leading_until() const {
    if (state_ != State::leader) return std::nullopt;
    return last_acknowledged_.value_or(claimed_at_) + fence_after();
}

std::optional<LeaderRecord> Lease::tick(MonoTime now) {
    if (state_ != State::standby && fenced(now)) {
        // A claim never acknowledged may sit in a buffer still: none other behind it.
        if (state_ == State::claiming && last_acknowledged_ < last_sent_) {
            unanswered_claim_ = last_sent_;
        }
        // Nobody is known to lead now.
        leader_id_.clear();
        stand_by(now);
    }
    if (state_ == State::standby) {
        if (path_back_ && !unanswered_claim_) last_heard_ = now;
        path_back_ = false;
        if (!connected_ || unanswered_claim_) return std::nullopt;
        // A renewal interval early, so that the claim stands (below) as the takeover is due.
        if (now - last_heard_ < settings_.takeover - renew_interval()) return std::nullopt;
        state_ = State::claiming;
        ++epoch_;
        leader_id_ = settings_.id;
        named_ = heard_;
        claimed_at_ = now;
        last_sent_ = now;
        last_acknowledged_.reset();
        echoed_ = false;
        return own_record();
    }
    if (state_ == State::claiming && last_acknowledged_ && echoed_ &&
        now - claimed_at_ >= renew_interval()) {
        state_ = State::leader;
        led_at_ = now;
    }
    if (now - last_sent_ < renew_interval() && !(reassert_ && state_ == State::leader)) {
        return std::nullopt;
    }
    reassert_ = false;
    last_sent_ = now;
    return own_record();
}

Role Lease::role(MonoTime now) const {
    return state_ == State::leader && !fenced(now) ? Role::leader : Role::standby;
}

bool Lease::may_produce(MonoTime now) const {
    // The leader last heard was fenced at last_heard_ + fence_after() at the latest, so its last
    // datagram is a period behind from then on.
    return role(now) == Role::leader &&
           now - last_heard_ >= fence_after() + settings_.longest_period;
}

WritePolicy Lease::writes(MonoTime now) const {
    // A unit that does not lead answers no write, whatever it knows of the leader: a live one
    // answers it; else the unit that leads next settles it (PairWrites), this one included,
    // having heard no answer. A refusal here could contradict either: the other unit heard the
    // write too, and this unit may be cut off without knowing (its path back delivers the
    // writes and the leader's answers together), or lose the claim it makes.
    return role(now) == Role::leader ? WritePolicy::apply : WritePolicy::leave_to_leader;
}

}  // namespace eip2mqtt::core::redundancy
