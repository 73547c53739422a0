#include "eip2mqtt/app/redundancy/pair.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iterator>
#include <utility>

#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"
#include "eip2mqtt/app/northbound/fan_out.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"
#include "eip2mqtt/app/redundancy/leader_publisher.hpp"
#include "eip2mqtt/app/redundancy/pair_lease.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/json_text.hpp"
#include "eip2mqtt/core/redundancy/answer_key.hpp"

namespace eip2mqtt::app::redundancy {
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

Pair::Pair(boost::asio::any_io_executor loop, const core::Clock& clock)
    : Pair(clock, mqtt_pair_connector(std::move(loop))) {}

Pair::Pair(const core::Clock& clock, PairConnector connect)
    : clock_(clock), connect_(std::move(connect)) {}

Pair::~Pair() = default;

std::function<bool(const adapters::mqtt::Message&)> Pair::may_send(
    std::function<bool(const adapters::mqtt::Message&)> leader_only) {
    return [this, leader_only = std::move(leader_only)](const adapters::mqtt::Message& message) {
        if (leader_only && !leader_only(message)) return true;
        return clock_.monotonic().time_since_epoch().count() <
               leading_until_.load(std::memory_order_acquire);
    };
}

ExchangesOptions Pair::exchanges_options() {
    ExchangesOptions options;
    options.role = this;
    return options;
}

WriteTurn Pair::admit_write(WriteRequest& request, core::write::WriteCounters& counters) {
    return admission_->admit_write(request, counters);
}

WriteTurn Pair::settle_write(const WriteRequest& request, core::write::WriteCounters& counters) {
    return admission_->settle_write(request, counters);
}

core::write::WriteRejection Pair::refusal() const { return admission_->refusal(); }

bool Pair::follows_produced(core::MonoTime now) const { return !lease_->leading(now); }

void Pair::image_changed(const ExchangeProducer& producer) {
    // Only a leader produces, so only a leader's images change by writes.
    images_->publish(producer, lease_->lease().epoch());
}

void Pair::answer_write(const ExchangeProducer& producer, std::uint64_t write_id,
                        const WriteReply& reply, std::function<void()> answer) {
    images_->answer_after_image(producer, write_id, reply, clock_.monotonic(), std::move(answer));
}

std::unique_ptr<adapters::mqtt::Publisher> Pair::leader_only(adapters::mqtt::Publisher& inner) {
    // Asked only once wire() made the lease: nothing is published before start().
    return std::make_unique<LeaderPublisher>(inner, [this] { return leading(clock_.monotonic()); });
}

bool Pair::leading(core::MonoTime now) const { return lease_->leading(now); }

bool Pair::may_produce(core::MonoTime now) const { return lease_->may_produce(now); }

std::string Pair::status_json() const {
    if (!lease_ || !parts_) return "null";
    const auto now = clock_.monotonic();
    const bool leads_now = leading(now);
    std::string out = R"({"pair":)";
    core::append_json_string(out, parts_->config.redundancy.pair);
    fmt::format_to(std::back_inserter(out), R"(,"role":"{}","epoch":{},"lease_left_ms":)",
                   leads_now ? "leader" : "standby", lease_->lease().epoch());
    const auto until = lease_->lease().leading_until();
    out += leads_now && until
               ? std::to_string(
                     std::chrono::duration_cast<std::chrono::milliseconds>(*until - now).count())
               : std::string("null");
    return out + '}';
}

void Pair::wire(PairParts parts) {
    const auto& parts_ref = parts_.emplace(std::move(parts));
    const auto& config = parts_ref.config;
    const auto& section = config.redundancy;
    auto topics = pair_topics(config.mqtt.base_topic, section.pair, config.gateway.id);
    client_ = connect_(config, pair_will(topics));
    images_ = std::make_unique<PairImages>(topics.images, config.gateway.id, *client_,
                                           write_horizon(config));
    core::redundancy::LeaseSettings settings{config.gateway.id, section.priority.value_or(0),
                                             section.takeover, longest_produced_period(config)};
    lease_ = std::make_unique<PairLease>(std::move(settings), std::move(topics), *client_,
                                         clock_.monotonic(),
                                         [this](core::redundancy::Role role) { on_role(role); });
    lease_->set_on_epoch_raised([this] { publish_images(); });
    if (parts_ref.session.bd_seq) lease_->set_bd_seq_source(parts_ref.session.bd_seq);
    parts_ref.north.set_role(*this);
    make_writes();
    make_history();
    spdlog::info("pair {}: standing by until the lease is settled (takeover after {} ms)",
                 section.pair, section.takeover.count());
}

void Pair::make_writes() {
    auto& parts = *parts_;
    writes_ = std::make_unique<PairWrites>(write_horizon(parts.config),
                                           [this] { parts_->tree.listen_again(); });
    parts.tree.set_answer_listener(
        [this](const adapters::mqtt::Incoming& answer) { writes_->heard(answer); },
        [this] { return writes_->response_topics(); });
    admission_ = std::make_unique<PairAdmission>(PairAdmission::Hooks{
        [this] { return lease_->writes(clock_.monotonic()); },
        [this](WriteRequest&& request) { writes_->leave(std::move(request), clock_.monotonic()); },
        [this](const ExchangeWrite& write) { return parts_->exchanges.holds(write); }});
    parts.writes.set_role(*this);
}

void Pair::make_history() {
    auto& parts = *parts_;
    // `_history` is the JSON tree's: a Sparkplug node alone has none to replay on.
    if (parts.config.sparkplug.enabled() && !parts.config.sparkplug.uns) return;
    history_ = std::make_unique<PairHistory>(
        PairHistoryOptions{parts.config.redundancy.takeover}, parts.tree,
        [this] { return parts_->tree_backlog(); }, clock_);
    history_->set_replay_gate(
        [this] { return lease_->lease().renewed_since_leading(clock_.monotonic()); });
    if (parts.session.history != nullptr) {
        history_->add_session_sink(*parts.session.history, parts.session.history_ready,
                                   parts.session.history_backlog);
    }
    parts.north.set_tap(*history_);
    parts.tree.set_sample_tokens(
        [this](const SampleBatch& batch) { return history_->token_for(batch); });
    lease_->set_watermarks(
        [this] { return history_->watermarks(); },
        [this](Watermarks&& watermarks) { history_->heard(std::move(watermarks)); });
}

void Pair::start() {
    client_->set_on_connected([this] {
        images_->reconnected();
        lease_->on_connected();
    });
    client_->set_on_message(
        [this](const adapters::mqtt::Incoming& message) { on_message(message); });
    client_->set_on_acknowledged([this](std::uint64_t token) { on_pair_acknowledged(token); });
    client_->start();
}

void Pair::tick(core::MonoTime now) {
    lease_->on_connection(client_->connected(), now);
    lease_->tick(now);
    refresh_leading_until();
}

void Pair::tick_replay() {
    if (history_) history_->on_tick();
}

void Pair::stop(std::chrono::milliseconds flush_timeout) { client_->stop(flush_timeout); }

bool Pair::on_acknowledged(std::uint64_t token) {
    return history_ && history_->on_acknowledged(token);
}

void Pair::publish_images() {
    for (const auto& producer : parts_->exchanges.producers()) {
        images_->publish(*producer, lease_->lease().epoch());
    }
}

void Pair::on_message(const adapters::mqtt::Incoming& message) {
    const auto now = clock_.monotonic();
    if (!images_->owns(message.topic)) {
        lease_->on_message(message, now);
        images_->other_leads(lease_->others_renewed_epoch());
        return refresh_leading_until();
    }
    images_->on_message(message, parts_->exchanges.producers(),
                        {lease_->leading(now), lease_->lease().epoch(), lease_->others_epoch(),
                         lease_->lease().claim_heard_back()});
}

void Pair::on_pair_acknowledged(std::uint64_t token) {
    if (images_->on_acknowledged(token, lease_->leading(clock_.monotonic()))) return;
    lease_->on_acknowledged(token);
    refresh_leading_until();
}

void Pair::refresh_leading_until() {
    const auto until = lease_->lease().leading_until().value_or(core::MonoTime::min());
    leading_until_.store(until.time_since_epoch().count(), std::memory_order_release);
}

void Pair::on_role(core::redundancy::Role role) {
    const auto now = clock_.monotonic();
    // Before anything is said as leader (the republish), or so that nothing more is.
    refresh_leading_until();
    auto& session = parts_->session;
    if (role == core::redundancy::Role::leader) {
        settle_left_writes(now);
        // What the old leader had not had acknowledged goes on `_history` before anything
        // live: the replay takes the window as it stands now.
        if (history_) history_->took_over(now);
        // The images under this lease's epoch, whatever the retained ones are: a standby that
        // starts later follows this leader's, not an older one's.
        publish_images();
        // A standby kept its exchanges current without a word north: the new leader says all
        // of it at once, over what the old leader left retained, and its Sparkplug births
        // hold it.
        parts_->republish();
        if (session.open) session.open(lease_->heard_bd_seq());
        return;
    }
    if (session.end) session.end();
    if (history_) history_->stood_by();
    step_down_writes(now);
}

void Pair::settle_left_writes(core::MonoTime now) {
    // What the other unit's images list as answered is not answered again: neither the writes
    // left to it, nor those this unit withheld when it last stood down (answered now if not).
    const auto listed = images_->take_leader_answers();
    images_->answer_withheld(listed, now, lease_->others_renewed_epoch());
    auto taken = writes_->take_unanswered(now, listed);
    for (const auto& write : taken.listed) repeat_answer(write);
    // The others are settled by the image as it stands: the one the old leader last published.
    for (auto& request : taken.unanswered) {
        const auto* write = std::get_if<ExchangeWrite>(&request.outcome);
        const auto* plan = write != nullptr ? write->producer : nullptr;
        const auto key =
            core::redundancy::answer_key(request.reply.topic, request.reply.correlation_data);
        // A refusal is listed in the images as well: whoever leads next answers it no more.
        if (!parts_->writes.settle(std::move(request)) && plan)
            images_->list_refusal(*plan, key, now);
    }
}

void Pair::repeat_answer(const ListedWrite& write) {
    // The old leader's answer was not heard here: it may never have left (the leader died
    // between the broker's acknowledgement of the image and its answer). Its client may get
    // the same answer twice, never two different ones. Through the fan-out, as every result:
    // the write log notes it too.
    const auto& reply = write.request.reply;
    switch (write.result) {
        case core::redundancy::ListedResult::ok:
            return parts_->north.write_result(reply, std::nullopt);
        case core::redundancy::ListedResult::refused:
            return parts_->north.write_result(reply, admission_->refusal().message);
        case core::redundancy::ListedResult::unknown:
            return;  // an older release's image: it does not say which answer to repeat
    }
}

void Pair::step_down_writes(core::MonoTime now) {
    // Accepted and produced, but the broker had not acknowledged the image listing them: given
    // only if the broker has it before any claim of the other unit (PairImages), else withheld
    // and settled by the unit that takes over, by the image it has.
    images_->stood_down();
    // Accepted and not produced: never produced by this unit, not even should it lead again
    // (the new leader may have taken them). An answer now could contradict the unit that
    // takes the lead, which settles them too (the other unit left them: it heard them), and a
    // unit cut off would say it only once its path is back, after that one. So they are left
    // as the other unit left them: whichever leads next settles them, and this unit forgets
    // each once it hears the answer. The command port's and Sparkplug's reach this unit
    // alone: answered `standby`.
    std::size_t cancelled = 0;
    for (const auto& producer : parts_->exchanges.producers()) {
        for (auto& request : producer->take_queued_writes()) {
            ++cancelled;
            if (request.reply.via == core::write::WriteOrigin::mqtt) {
                writes_->leave(std::move(request), now);
            } else if (request.reply.origin) {
                parts_->north.write_result(request.reply, "standby");
            }
        }
    }
    parts_->writes.count_cancelled(cancelled);
}

}  // namespace eip2mqtt::app::redundancy
