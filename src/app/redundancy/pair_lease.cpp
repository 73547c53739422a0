#include "eip2mqtt/app/redundancy/pair_lease.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <utility>

#include "eip2mqtt/app/redundancy/leader_record.hpp"

namespace eip2mqtt::app::redundancy {
namespace {

using LeaseRole = core::redundancy::Role;

/// A publication's acknowledgement token is the time it was sent: the lease counts a renewal
/// as of then. Never 0 (which means none): the steady clock is far past its epoch.
std::uint64_t token_of(core::MonoTime sent_at) {
    return static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(sent_at.time_since_epoch()).count());
}

core::MonoTime time_of(std::uint64_t token) {
    return core::MonoTime(std::chrono::duration_cast<core::MonoTime::duration>(
        std::chrono::nanoseconds(static_cast<std::int64_t>(token))));
}

}  // namespace

PairTopics pair_topics(const std::string& base_topic, const std::string& pair,
                       const std::string& id) {
    return {base_topic + "/_gateway/_pair/" + pair + "/leader",
            base_topic + "/_gateway/" + id + "/role",
            base_topic + "/_gateway/_pair/" + pair + "/image"};
}

adapters::mqtt::Message pair_will(const PairTopics& topics) {
    adapters::mqtt::Message will;
    will.topic = topics.leader;
    will.qos = 1;
    will.retain = true;
    return will;
}

PairLease::PairLease(core::redundancy::LeaseSettings settings, PairTopics topics,
                     adapters::mqtt::Publisher& publisher, core::MonoTime start,
                     RoleChanged on_role)
    : lease_(settings, start),
      takeover_(settings.takeover),
      topics_(std::move(topics)),
      publisher_(publisher),
      on_role_(std::move(on_role)) {
    // One list for the connection: the images' readers share it (PairImages).
    publisher_.set_subscriptions({topics_.leader, topics_.images + "/#"});
}

void PairLease::on_connected() { publish_role(role_); }

void PairLease::on_message(const adapters::mqtt::Incoming& message, core::MonoTime now) {
    if (message.topic != topics_.leader) return;
    const auto record = decode_leader_record(message.payload, &heard_);
    if (record && record->id != lease_.id()) {
        others_epoch_ = std::max(others_epoch_, record->epoch);
        if (!record->claim) others_renewed_ = std::max(others_renewed_, record->epoch);
    }
    const bool followed = lease_.on_record(record, now);
    if (record && record->bd_seq && record->epoch >= lease_.epoch()) {
        heard_bd_seq_ = record->bd_seq;
    }
    // The renewals of the leader this unit follows (below the epoch a failed claim of its own
    // raised, too): a claim has acknowledged nothing yet, and a deposed leader's renewal,
    // late, is not followed.
    if (watermarks_heard_ && followed && !record->claim) {
        watermarks_heard_(std::move(heard_));
    }
    follow_role(now);
}

void PairLease::on_acknowledged(std::uint64_t token) { lease_.on_acknowledged(time_of(token)); }

void PairLease::tick(core::MonoTime now) {
    if (auto record = lease_.tick(now)) {
        if (record->claim && record->epoch != claimed_epoch_) {
            claimed_epoch_ = record->epoch;
            spdlog::info("pair: claiming the lead, epoch {}", record->epoch);
        }
        if (!record->claim && bd_seq_source_) record->bd_seq = bd_seq_source_();
        message_.topic = topics_.leader;
        message_.payload = encode_leader_record(
            *record, takeover_,
            !record->claim && watermarks_now_ ? watermarks_now_() : Watermarks{});
        message_.qos = 1;
        message_.retain = true;
        message_.ack_token = token_of(now);
        publisher_.publish(std::move(message_));
    }
    follow_role(now);
}

void PairLease::follow_role(core::MonoTime now) {
    const auto role = lease_.role(now);
    if (role == LeaseRole::leader && role_ == LeaseRole::leader && lease_.epoch() != led_epoch_) {
        led_epoch_ = lease_.epoch();
        spdlog::warn("pair: a stale claim renewed over, leading on under epoch {}", led_epoch_);
        if (on_epoch_raised_) on_epoch_raised_();
    }
    if (role == role_) {
        if (role == LeaseRole::leader) led_until_ = lease_.leading_until();
        return;
    }
    role_ = role;
    if (role == LeaseRole::leader) {
        led_epoch_ = lease_.epoch();
        led_until_ = lease_.leading_until();
        spdlog::info("pair: leading, epoch {}", lease_.epoch());
    } else if (lease_.leader_id().empty() && led_until_ && now >= *led_until_) {
        spdlog::warn(
            "pair: standing by, epoch {}: no renewal acknowledged in time (the lease ran out {} "
            "ms ago)",
            lease_.epoch(),
            std::chrono::duration_cast<std::chrono::milliseconds>(now - *led_until_).count());
    } else {
        spdlog::warn(
            "pair: standing by{}, epoch {}",
            lease_.leader_id().empty() ? std::string() : " (leader " + lease_.leader_id() + ")",
            lease_.epoch());
    }
    publish_role(role);
    if (on_role_) on_role_(role);
}

void PairLease::publish_role(LeaseRole role) {
    message_.topic = topics_.role;
    message_.payload = std::string(core::redundancy::to_string(role));
    message_.qos = 1;
    message_.retain = true;
    message_.text = true;  // `leader` or `standby`
    publisher_.publish(std::move(message_));
}

}  // namespace eip2mqtt::app::redundancy
