// Store and forward in the gateway: the journal under gateway.state_dir, fed by the
// exchanges through the fan-out while MQTT is down, replayed on the JSON tree's `_history`.

#include <spdlog/spdlog.h>

#include <filesystem>

#include "eip2mqtt/app/gateway.hpp"

namespace eip2mqtt::app {

void Gateway::make_history() {
    const auto& settings = config_.mqtt.store_and_forward;
    if (!settings.enabled) return;
    adapters::history::JournalOptions options;
    options.path = (std::filesystem::path(config_.gateway.state_dir) / "history.sqlite").string();
    options.max_bytes = settings.max_mb << 20;
    std::unique_ptr<adapters::history::Journal> journal;
    try {
        std::filesystem::create_directories(config_.gateway.state_dir);
        std::string set_aside;
        journal = adapters::history::Journal::open(options, set_aside);
        if (!set_aside.empty()) spdlog::warn("store and forward: {}", set_aside);
    } catch (const std::exception& error) {
        spdlog::error(
            "store and forward is off: the journal {} cannot be opened ({}); check that "
            "gateway.state_dir is writable by the service",
            options.path, error.what());
        return;
    }
    // The journal and the JSON tree ask the same connection whether it is up, at the same
    // moment on the same loop: every sample goes either live or to the journal.
    const auto connected = [this] { return mqtt_->connected(); };
    history::LinkProbe link{connected, [this] {
                                const auto stats = mqtt_->stats();
                                return stats.queued + stats.in_flight;
                            }};
    history_ = std::make_unique<history::StoreAndForward>(
        std::move(journal),
        history::StoreAndForwardOptions{settings.replay_rate, settings.fsync_interval},
        std::move(link), *json_tree_);
    json_tree_->set_store_and_forward(connected);
    northbound_.add(*history_);
    const auto stats = history_->stats();
    spdlog::info("store and forward: journal {} ({} entries, bound {} MB)", options.path,
                 stats.journal.entries, settings.max_mb);
}

void Gateway::add_sparkplug_history() {
    if (!history_) return;
    history::LinkProbe link{[this] { return sparkplug_mqtt_->connected() && sparkplug_->born(); },
                            [this] {
                                const auto stats = sparkplug_mqtt_->stats();
                                return stats.queued + stats.in_flight;
                            }};
    // Its acknowledgements come through the node's handler (Gateway::start), which shares the
    // connection's tokens with the node's own NDEATH.
    history_->add_sink(*sparkplug_, std::move(link));
}

void Gateway::on_sparkplug_event(bool connection, const std::function<void()>& event) {
    // Born by this event (a connection without a primary host, the host's STATE online, the
    // PUBACK of an NDEATH a birth waited for, or a pending rebirth on a tick): the node replays
    // on the births' heels. Every birth comes from one of these, and what the node was handed
    // while it was born before and had not had acknowledged goes again.
    const bool was_born = !connection && sparkplug_->born();
    event();
    if (history_ && sparkplug_->born() && !was_born) {
        history_->on_connected(*sparkplug_, clock_.monotonic());
    }
}

}  // namespace eip2mqtt::app
