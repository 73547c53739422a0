#include "eip2mqtt/app/history/sink_replay.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

namespace eip2mqtt::app::history {
namespace {

/// Live publications waiting beyond this hold the replay back: live data goes first.
constexpr std::uint64_t kLiveBacklog = 1000;
/// Replayed entries unacknowledged at most: a window's worth keeps the broker busy without
/// filling the client's queue with history.
constexpr std::size_t kMaxOutstanding = 1000;
/// Ticks the client must hold none of the outstanding entries before they count as dropped:
/// an acknowledgement posted to the loop just before may still be on its way for one tick.
constexpr int kIdleTicksBeforeRewind = 2;
/// How long a sink must have stayed connected after entries were journaled for them to count
/// as published live: a connection that went is noticed well within it (the broker's close).
constexpr auto kLiveGrace = std::chrono::seconds(2);

}  // namespace

void SinkReplay::start(core::MonoTime now, bool rewind_first) {
    if (rewind_first) {
        cursor_ = through();
        outstanding_.clear();
    }
    active_ = true;
    idle_with_outstanding_ = 0;
    last_ = now;
    allowance_ = 0;
}

std::size_t SinkReplay::room(core::MonoTime now, double rate) {
    if (!link_.connected()) {
        last_ = now;
        return 0;
    }
    const auto elapsed = std::chrono::duration<double>(now - last_.value_or(now)).count();
    allowance_ = std::min(allowance_ + rate * elapsed, std::max(1.0, rate / 10));
    last_ = now;
    const auto backlog = link_.backlog();
    if (!outstanding_.empty() && backlog == 0) {
        // The client holds none of them and never acknowledged them: it dropped them (a full
        // queue, a refusal). They go again.
        if (++idle_with_outstanding_ >= kIdleTicksBeforeRewind) rewind();
        return 0;
    }
    idle_with_outstanding_ = 0;
    if (backlog > kLiveBacklog) return 0;
    const auto room = std::min<double>(allowance_, kMaxOutstanding - outstanding_.size());
    return room < 1 ? 0 : static_cast<std::size_t>(room);
}

void SinkReplay::handed(std::uint64_t id, bool outstanding) {
    cursor_ = id;
    allowance_ -= 1;
    if (outstanding) outstanding_.insert(id);
}

void SinkReplay::note_live(core::MonoTime now, std::uint64_t last_id) {
    if (active_ || !link_.connected()) {
        live_since_.reset();
        return;
    }
    if (live_since_ && now - *live_since_ >= kLiveGrace && outstanding_.empty()) {
        cursor_ = std::max(cursor_, live_mark_);
    }
    if (!live_since_ || now - *live_since_ >= kLiveGrace) {
        live_since_ = now;
        live_mark_ = last_id;
    }
}

void SinkReplay::paced(std::size_t handed, bool out_of_time) {
    pace_ = out_of_time ? std::max<std::size_t>(1, 2 * handed) : SIZE_MAX;
}

bool SinkReplay::acknowledge(std::uint64_t id) { return outstanding_.erase(id) > 0; }

void SinkReplay::rewind() {
    spdlog::warn(
        "store and forward: {} replayed entries were never acknowledged (the MQTT client dropped "
        "them); they go again",
        outstanding_.size());
    cursor_ = through();  // what went before them is delivered
    outstanding_.clear();
    idle_with_outstanding_ = 0;
}

}  // namespace eip2mqtt::app::history
