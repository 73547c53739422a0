#include "eip2mqtt/app/northbound/sparkplug/sparkplug_module.hpp"

#include <spdlog/spdlog.h>

#include <chrono>

#include "eip2mqtt/app/exchanges/write_dispatcher.hpp"
#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/history/store_and_forward.hpp"
#include "eip2mqtt/app/northbound/mqtt_settings.hpp"
#include "eip2mqtt/app/redundancy/role.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using namespace std::chrono_literals;

// How long a clean stop waits for queued publications before giving up.
constexpr auto stop_flush_timeout = 3s;

}  // namespace

SparkplugModule::SparkplugModule(const core::config::Config& config, const NorthboundParts& parts,
                                 history::StoreAndForward* history)
    : clock_(parts.clock), history_(history), opens_at_start_(!parts.role.sessions_follow_role()) {
    auto options = sparkplug_client_options(config, [this] { return node_->next_will(); });
    // A session held with the role is the role holder's: all of it (its NDEATH goes another
    // way).
    options.may_send = parts.role.may_send(nullptr);
    client_ = std::make_unique<adapters::mqtt::Client>(parts.loop, std::move(options));
    gate_ = parts.role.session_gate(*client_);
    adapters::mqtt::Publisher& publisher = gate_ ? *gate_ : *client_;
    node_ =
        std::make_unique<SparkplugNode>(sparkplug_options(config), publisher, parts.writes, clock_);
    add_history();
}

void SparkplugModule::add_history() {
    if (history_ == nullptr) return;
    history::LinkProbe link{[this] { return client_->connected() && node_->born(); },
                            [this] {
                                const auto stats = client_->stats();
                                return stats.queued + stats.in_flight;
                            }};
    // Its acknowledgements come through the node's handler (start()), which shares the
    // connection's tokens with the node's own NDEATH.
    history_->add_sink(*node_, std::move(link));
}

void SparkplugModule::start(core::MonoTime /*now*/) {
    client_->set_on_connected(
        [this] { on_event(true, [this] { node_->on_connected(client_->max_packet_size()); }); });
    // One handler for both owners of the tokens on the node's connection: the node's own
    // NDEATH (whose acknowledgement may let a pending birth go), else a journal entry.
    client_->set_on_acknowledged([this](std::uint64_t token) {
        on_event(false, [&] {
            if (!node_->on_acknowledged(token) && history_)
                history_->on_acknowledged(*node_, token);
        });
    });
    client_->set_on_message([this](const adapters::mqtt::Incoming& message) {
        on_event(false, [&] { node_->on_message(message); });
    });
    if (opens_at_start_) client_->start();
}

void SparkplugModule::tick(const TickTimes& times) {
    // A pending rebirth may be born here: the node's replay of history starts with it.
    on_event(false, [&] { node_->tick(times.now); });
}

void SparkplugModule::on_event(bool connection, const std::function<void()>& event) {
    // Born by this event (a connection without a primary host, the host's STATE online, the
    // PUBACK of an NDEATH a birth waited for, or a pending rebirth on a tick): the node replays
    // on the births' heels. Every birth comes from one of these, and what the node was handed
    // while it was born before and had not had acknowledged goes again.
    const bool was_born = !connection && node_->born();
    event();
    if (history_ && node_->born() && !was_born) history_->on_connected(*node_, clock_.monotonic());
}

void SparkplugModule::stop() { client_->stop(stop_flush_timeout); }

void SparkplugModule::apply(const core::config::Config& next) {
    client_->set_buffer_capacity(next.mqtt.buffer_max_messages);
    client_->set_batch_first(next.mqtt.batch_first);
}

void SparkplugModule::add_metrics(MetricsSources& sources) { sources.sparkplug = &node_->stats(); }

void SparkplugModule::open_session(std::optional<std::uint8_t> heard_bd_seq) {
    node_->begin_session(heard_bd_seq);
    client_->start();  // the CONNECT's will, made now, takes the session's bdSeq
    if (const auto bd_seq = node_->session_bd_seq()) {
        spdlog::info("Sparkplug: the edge node's session opens with bdSeq {}", *bd_seq);
    }
}

void SparkplugModule::end_session() {
    const auto bd_seq = node_->session_bd_seq();
    if (!bd_seq) return;
    // A host must see the node die, and nothing of this session once another unit's has
    // begun: what waits is dropped, not flushed, and the NDEATH goes last. The other unit's
    // NBIRTH carries another bdSeq, so an NDEATH of this one delivered after it ends nothing.
    client_->end_session();
    node_->end_session();
    spdlog::info("Sparkplug: the edge node's session with bdSeq {} ended (NDEATH)", *bd_seq);
}

std::unique_ptr<SparkplugModule> make_sparkplug(const core::config::Config& config,
                                                const NorthboundParts& parts,
                                                history::StoreAndForward* history) {
    if (!config.sparkplug.enabled()) return nullptr;
    return std::make_unique<SparkplugModule>(config, parts, history);
}

}  // namespace eip2mqtt::app::northbound::sparkplug
