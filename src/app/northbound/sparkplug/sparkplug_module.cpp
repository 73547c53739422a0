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
    : clock_(parts.clock),
      history_(history),
      opens_at_start_(!parts.role.sessions_follow_role()),
      bd_seq_file_(config.gateway.state_dir + "/" + std::string(bd_seq_file_name)) {
    auto options = sparkplug_client_options(config, [this] { return next_will(); });
    // A session held with the role is the role holder's: all of it (its NDEATH goes another
    // way).
    options.may_send = parts.role.may_send(nullptr);
    client_ = std::make_unique<adapters::mqtt::Client>(parts.loop, std::move(options));
    gate_ = parts.role.session_gate(*client_);
    adapters::mqtt::Publisher& publisher = gate_ ? *gate_ : *client_;
    auto node_options = sparkplug_options(config);
    node_options.last_bd_seq = kept_bd_seq_ = bd_seq_file_.read();
    // The primary host offline: the node's session with this broker ends, the next is tried.
    node_ = std::make_unique<SparkplugNode>(std::move(node_options), publisher, parts.writes,
                                            clock_, [this] { client_->leave_broker(); });
    add_history();
}

adapters::mqtt::Message SparkplugModule::next_will() {
    auto will = node_->next_will();
    // Before the CONNECT that carries it: a restart goes on from it, whatever came after.
    if (kept_bd_seq_ != node_->bd_seq()) {
        kept_bd_seq_ = node_->bd_seq();
        bd_seq_file_.write(*kept_bd_seq_);
    }
    return will;
}

std::uint64_t SparkplugModule::backlog() const {
    const auto stats = client_->stats();
    return stats.queued + stats.in_flight;
}

void SparkplugModule::add_history() {
    if (history_ == nullptr) return;
    history::LinkProbe link{[this] { return client_->connected() && node_->may_send_data(); },
                            [this] { return backlog(); }};
    // Its acknowledgements come through the node's handler (start()), which shares the
    // connection's tokens with the node's own NDEATH.
    history_->add_sink(*node_, std::move(link));
}

void SparkplugModule::start(core::MonoTime /*now*/) {
    client_->set_on_connected(
        [this] { on_event(true, [this] { node_->on_connected(client_->max_packet_size()); }); });
    // The tokens on the node's connection are the journal entries of its historical DDATA.
    if (history_) {
        client_->set_on_acknowledged(
            [this](std::uint64_t token) { history_->on_acknowledged(*node_, token); });
    }
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
    // Born by this event (a connection without a primary host, the host's STATE online, or a
    // waiting rebirth on a tick): the node replays on the births' heels. Every birth comes from one
    // of these, and what the node was handed while it was born before and had not had acknowledged
    // goes again.
    const bool was_born = !connection && node_->born();
    event();
    if (history_ && node_->born() && !was_born) history_->on_connected(*node_, clock_.monotonic());
}

void SparkplugModule::stop() { client_->stop(stop_flush_timeout); }

void SparkplugModule::apply(const core::config::Config& next) {
    const auto& mqtt =
        core::config::mqtt_connection(next, core::config::sparkplug_connection(next));
    client_->set_buffer_capacity(mqtt.buffer_max_messages);
    client_->set_batch_first(mqtt.batch_first);
}

void SparkplugModule::add_metrics(MetricsSources& sources) {
    node_->refresh_session();
    sources.sparkplug = &node_->stats();
}

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
