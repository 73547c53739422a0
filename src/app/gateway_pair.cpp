// A hot-standby pair (docs/redundancy.md): the lease on its own connection, and the three
// gates it keeps, one each: what the exchanges say north (the FanOut), what they produce (the
// ProducerScheduler, through Exchanges' options) and the writes (the WriteDispatcher). And what
// lets a takeover go on where the leader stopped: its images, published by the leader and
// followed by the standby (PairImages), its request ids, heard by the standby
// (DatagramRouter::set_followed), its samples: the new leader publishes on `_history` those
// the old one had not had acknowledged (PairHistory), and the Sparkplug session of the one edge
// node, held by the leader alone.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/northbound/mqtt_settings.hpp"
#include "eip2mqtt/core/redundancy/answer_key.hpp"

namespace eip2mqtt::app {
namespace {

/// The longest period of the produced exchanges: a new leader waits it out before producing.
std::chrono::milliseconds longest_produced_period(const core::config::Config& config) {
    std::chrono::milliseconds longest{0};
    for (const auto& exchange : config.exchanges) {
        if (exchange.spec.direction == core::plan::Direction::produce) {
            longest = std::max(longest, exchange.spec.period);
        }
    }
    return longest;
}

/// How long a live leader may take to answer a write: a production, a save and an image's
/// acknowledgement. Twice the takeover and two of the longest periods is past any of it.
std::chrono::milliseconds write_horizon(const core::config::Config& config) {
    return 2 * config.redundancy.takeover + 2 * longest_produced_period(config);
}

}  // namespace

void Gateway::make_pair() {
    const auto& section = config_.redundancy;
    if (!section.enabled()) return;
    auto topics =
        redundancy::pair_topics(config_.mqtt.base_topic, section.pair, config_.gateway.id);
    pair_mqtt_ = std::make_unique<adapters::mqtt::Client>(
        loop_.get_executor(), pair_client_options(config_, redundancy::pair_will(topics)));
    pair_images_ = std::make_unique<redundancy::PairImages>(topics.images, config_.gateway.id,
                                                            *pair_mqtt_, write_horizon(config_));
    core::redundancy::LeaseSettings settings{config_.gateway.id, section.priority.value_or(0),
                                             section.takeover, longest_produced_period(config_)};
    pair_ = std::make_unique<redundancy::PairLease>(
        std::move(settings), std::move(topics), *pair_mqtt_, std::chrono::steady_clock::now(),
        [this](core::redundancy::Role role) { on_role(role); });
    pair_->set_on_epoch_raised([this] { publish_images(); });
    if (sparkplug_) pair_->set_bd_seq_source([this] { return sparkplug_->session_bd_seq(); });
    northbound_.set_gate([this] { return pair_->leading(std::chrono::steady_clock::now()); });
    make_pair_writes();
    make_pair_history();
    spdlog::info("pair {}: standing by until the lease is settled (takeover after {} ms)",
                 section.pair, section.takeover.count());
}

void Gateway::make_pair_writes() {
    pair_writes_ = std::make_unique<redundancy::PairWrites>(write_horizon(config_),
                                                            [this] { json_tree_->listen_again(); });
    json_tree_->set_answer_listener(
        [this](const adapters::mqtt::Incoming& answer) { pair_writes_->heard(answer); },
        [this] { return pair_writes_->response_topics(); });
    writes_.set_admission({[this] { return pair_->writes(std::chrono::steady_clock::now()); },
                           [this](WriteRequest&& request) {
                               pair_writes_->leave(std::move(request),
                                                   std::chrono::steady_clock::now());
                           },
                           [this](const ExchangeWrite& write) { return exchanges_.holds(write); }});
}

void Gateway::make_pair_history() {
    // `_history` is the JSON tree's: a Sparkplug node alone has none to replay on.
    if (config_.sparkplug.enabled() && !config_.sparkplug.uns) return;
    pair_history_ = std::make_unique<redundancy::PairHistory>(
        redundancy::PairHistoryOptions{config_.redundancy.takeover}, *json_tree_,
        [this] {
            const auto stats = mqtt_->stats();
            return stats.queued + stats.in_flight;
        },
        adapters::clock::system_clock());
    pair_history_->set_replay_gate(
        [this] { return pair_->lease().renewed_since_leading(std::chrono::steady_clock::now()); });
    northbound_.set_tap(*pair_history_);
    json_tree_->set_pair(
        [this](const SampleBatch& batch) { return pair_history_->token_for(batch); });
    pair_->set_watermarks([this] { return pair_history_->watermarks(); },
                          [this](redundancy::Watermarks&& watermarks) {
                              pair_history_->heard(std::move(watermarks));
                          });
}

void Gateway::on_acknowledged(std::uint64_t token) {
    if (pair_history_ && pair_history_->on_acknowledged(token)) return;
    if (history_) history_->on_acknowledged(token);
}

std::function<bool(const adapters::mqtt::Message&)> Gateway::pair_may_send(
    std::function<bool(const adapters::mqtt::Message&)> leader_only) {
    return [this, leader_only = std::move(leader_only)](const adapters::mqtt::Message& message) {
        if (leader_only && !leader_only(message)) return true;
        return std::chrono::steady_clock::now().time_since_epoch().count() <
               leading_until_.load(std::memory_order_acquire);
    };
}

void Gateway::refresh_leading_until() {
    const auto until =
        pair_->lease().leading_until().value_or(std::chrono::steady_clock::time_point::min());
    leading_until_.store(until.time_since_epoch().count(), std::memory_order_release);
}

ExchangesOptions Gateway::pair_options() {
    ExchangesOptions options;
    if (!config_.redundancy.enabled()) return options;
    // Each called only once make_pair() made the pair: exchanges run from start() on.
    options.may_produce = [this](core::MonoTime now) { return may_produce(now); };
    // Only a leader produces, so only a leader's images change by writes.
    options.on_image_changed = [this](const ExchangeProducer& producer) {
        pair_images_->publish(producer, pair_->lease().epoch());
    };
    options.answer_gate = [this](const ExchangeProducer& producer, std::uint64_t write_id,
                                 const WriteReply& reply, std::function<void()> answer) {
        pair_images_->answer_after_image(producer, write_id, reply,
                                         std::chrono::steady_clock::now(), std::move(answer));
    };
    options.follows_produced = [this](core::MonoTime now) { return !pair_->leading(now); };
    return options;
}

void Gateway::publish_images() {
    for (const auto& producer : exchanges_.producers()) {
        pair_images_->publish(*producer, pair_->lease().epoch());
    }
}

void Gateway::start_pair() {
    if (!pair_mqtt_) return;
    pair_mqtt_->set_on_connected([this] {
        pair_images_->reconnected();
        pair_->on_connected();
    });
    pair_mqtt_->set_on_message([this](const adapters::mqtt::Incoming& message) {
        const auto now = std::chrono::steady_clock::now();
        if (!pair_images_->owns(message.topic)) {
            pair_->on_message(message, now);
            pair_images_->other_leads(pair_->others_renewed_epoch());
            return refresh_leading_until();
        }
        pair_images_->on_message(message, exchanges_.producers(),
                                 {pair_->leading(now), pair_->lease().epoch(),
                                  pair_->others_epoch(), pair_->lease().claim_heard_back()});
    });
    pair_mqtt_->set_on_acknowledged([this](std::uint64_t token) {
        if (pair_images_->on_acknowledged(token,
                                          pair_->leading(std::chrono::steady_clock::now()))) {
            return;
        }
        pair_->on_acknowledged(token);
        refresh_leading_until();
    });
    pair_mqtt_->start();
}

void Gateway::on_role(core::redundancy::Role role) {
    const auto now = std::chrono::steady_clock::now();
    // Before anything is said as leader (the republish), or so that nothing more is.
    refresh_leading_until();
    if (role == core::redundancy::Role::leader) {
        settle_left_writes(now);
        // What the old leader had not had acknowledged goes on `_history` before anything
        // live: the replay takes the window as it stands now.
        if (pair_history_) pair_history_->took_over(now);
        // The images under this lease's epoch, whatever the retained ones are: a standby that
        // starts later follows this leader's, not an older one's.
        publish_images();
        // A standby kept its exchanges current without a word north: the new leader says all
        // of it at once, over what the old leader left retained, and its Sparkplug births
        // hold it.
        republish_exchanges();
        return open_sparkplug_session();
    }
    end_sparkplug_session();
    if (pair_history_) pair_history_->stood_by();
    step_down_writes(now);
}

void Gateway::settle_left_writes(core::MonoTime now) {
    // What the other unit's images list as answered is not answered again: neither the writes
    // left to it, nor those this unit withheld when it last stood down (answered now if not).
    const auto listed = pair_images_->take_leader_answers();
    pair_images_->answer_withheld(listed, now);
    // The others are settled by the image as it stands: the one the old leader last published.
    for (auto& request : pair_writes_->take_unanswered(now, listed)) {
        const auto* write = std::get_if<ExchangeWrite>(&request.outcome);
        const auto* plan = write != nullptr ? write->producer : nullptr;
        const auto key =
            core::redundancy::answer_key(request.reply.topic, request.reply.correlation_data);
        // A refusal is listed in the images as well: whoever leads next answers it no more.
        if (!writes_.settle(std::move(request)) && plan)
            pair_images_->list_refusal(*plan, key, now);
    }
}

void Gateway::step_down_writes(core::MonoTime now) {
    // Accepted and produced, but the broker had not acknowledged the image listing them: given
    // only if the broker has it before any claim of the other unit (PairImages), else withheld
    // and settled by the unit that takes over, by the image it has.
    pair_images_->stood_down();
    // Accepted and not produced: never produced by this unit, not even should it lead again
    // (the new leader may have taken them). An answer now could contradict the unit that
    // takes the lead, which settles them too (the other unit left them: it heard them), and a
    // unit cut off would say it only once its path is back, after that one. So they are left
    // as the other unit left them: whichever leads next settles them, and this unit forgets
    // each once it hears the answer. The command port's and Sparkplug's reach this unit
    // alone: answered `standby`.
    std::size_t cancelled = 0;
    for (const auto& producer : exchanges_.producers()) {
        for (auto& request : producer->take_queued_writes()) {
            ++cancelled;
            if (request.reply.via == core::write::WriteOrigin::mqtt) {
                pair_writes_->leave(std::move(request), now);
            } else if (request.reply.origin) {
                request.reply.origin->write_result(request.reply, "standby");
            }
        }
    }
    writes_.count_cancelled(cancelled);
}

}  // namespace eip2mqtt::app
