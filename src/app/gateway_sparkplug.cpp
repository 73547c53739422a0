// The Sparkplug B edge node in the gateway (docs/sparkplug.md): the node on a connection of its
// own, and, in a hot-standby pair, the session of the one edge node that only the leader holds
// (docs/redundancy.md). Its history is in gateway_history.cpp.

#include <spdlog/spdlog.h>

#include <chrono>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/app/gateway.hpp"
#include "eip2mqtt/app/northbound/mqtt_settings.hpp"

namespace eip2mqtt::app {

void Gateway::make_sparkplug() {
    if (!config_.sparkplug.enabled()) return;
    auto options = sparkplug_client_options(config_, [this] { return sparkplug_->next_will(); });
    // In a pair the node's session is the leader's: all of it (its NDEATH goes another way).
    if (pair_) options.may_send = pair_->may_send(nullptr);
    sparkplug_mqtt_ =
        std::make_unique<adapters::mqtt::Client>(loop_.get_executor(), std::move(options));
    adapters::mqtt::Publisher* node_mqtt = sparkplug_mqtt_.get();
    if (pair_) {
        sparkplug_leader_ = pair_->leader_only(*sparkplug_mqtt_);
        node_mqtt = sparkplug_leader_.get();
    }
    sparkplug_ = std::make_unique<northbound::sparkplug::SparkplugNode>(
        northbound::sparkplug::sparkplug_options(config_), *node_mqtt, writes_, clock_);
    northbound_.add(*sparkplug_);
    add_sparkplug_history();
}

void Gateway::open_sparkplug_session(std::optional<std::uint8_t> heard_bd_seq) {
    if (!sparkplug_) return;
    sparkplug_->begin_session(heard_bd_seq);
    sparkplug_mqtt_->start();  // the CONNECT's will, made now, takes the session's bdSeq
    if (const auto bd_seq = sparkplug_->session_bd_seq()) {
        spdlog::info("Sparkplug: the edge node's session opens with bdSeq {}", *bd_seq);
    }
}

void Gateway::end_sparkplug_session() {
    if (!sparkplug_) return;
    const auto bd_seq = sparkplug_->session_bd_seq();
    if (!bd_seq) return;
    // A host must see the node die, and nothing of this session once the new leader's has
    // begun: what waits is dropped, not flushed, and the NDEATH goes last. The other unit's
    // NBIRTH carries another bdSeq, so an NDEATH of this one delivered after it ends nothing.
    sparkplug_mqtt_->end_session();
    sparkplug_->end_session();
    spdlog::info("Sparkplug: the edge node's session with bdSeq {} ended (NDEATH)", *bd_seq);
}

}  // namespace eip2mqtt::app
