#include "eip2mqtt/core/redundancy/lease.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

namespace eip2mqtt::core::redundancy {

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
            return !record.claim && outranks(record);
    }
    return false;
}

void Lease::stand_by(MonoTime now) {
    state_ = State::standby;
    last_heard_ = now;
    last_acknowledged_.reset();
}

void Lease::on_record(const std::optional<LeaderRecord>& record, MonoTime now) {
    // An empty record (a will) says nothing the time since the last record does not.
    if (!record) return;
    read_a_record_ = true;
    if (record->id == settings_.id) {
        // Our own, or one from before a restart: its epoch is spent either way.
        epoch_ = std::max(epoch_, record->epoch);
        return;
    }
    const bool newer = record->epoch > epoch_;
    if (!newer && !(record->epoch == epoch_ && gives_way(*record))) return;
    epoch_ = record->epoch;
    leader_id_ = record->id;
    stand_by(now);
    lapsed_ = false;
}

void Lease::on_acknowledged(MonoTime sent_at) {
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
        // Nobody is known to lead now: writes are refused until a leader is heard.
        leader_id_.clear();
        stand_by(now);
        lapsed_ = true;
    }
    if (state_ == State::standby) {
        // A renewal interval early, so that the claim stands (below) as the takeover is due.
        if (now - last_heard_ < settings_.takeover - renew_interval()) return std::nullopt;
        state_ = State::claiming;
        ++epoch_;
        leader_id_ = settings_.id;
        claimed_at_ = now;
        last_sent_ = now;
        last_acknowledged_.reset();
        return own_record();
    }
    if (state_ == State::claiming && last_acknowledged_ && now - claimed_at_ >= renew_interval()) {
        state_ = State::leader;
        lapsed_ = false;
    }
    if (now - last_sent_ < renew_interval()) return std::nullopt;
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
    if (role(now) == Role::leader) return WritePolicy::apply;
    // Live while it may still hold its lease: a write it may answer is never refused here too.
    const bool live_leader = state_ == State::standby && !leader_id_.empty() &&
                             leader_id_ != settings_.id && now - last_heard_ < fence_after();
    // A unit whose lease lapsed (fenced, whether or not a tick has stepped it down yet) never
    // refuses: the other unit may have taken over meanwhile and answers the write, at once or
    // as one in doubt when it takes over; so does this one should it lead again first.
    const bool lapsed = lapsed_ || state_ == State::leader;
    // Started, and nothing read on the leader topic yet (its retained record comes on another
    // connection than the writes): should this unit take the lead instead, it refuses them then.
    const bool starting = state_ == State::standby && !read_a_record_;
    return live_leader || lapsed || starting ? WritePolicy::leave_to_leader : WritePolicy::refuse;
}

}  // namespace eip2mqtt::core::redundancy
