#include "eip2mqtt/app/history/store_and_forward_module.hpp"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <string>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"

namespace eip2mqtt::app::history {
namespace {

/// The journal's link: the JSON tree's connection. The journal and the tree ask it whether it
/// is up at the same moment on the same loop, so every sample goes either live or to the
/// journal.
LinkProbe tree_link(adapters::mqtt::Client& client) {
    return {[&client] { return client.connected(); },
            [&client] {
                const auto stats = client.stats();
                return stats.queued + stats.in_flight;
            }};
}

const core::config::StoreAndForwardSection& settings(
    const core::config::Config& config, const northbound::json_tree::JsonTreeModule& tree) {
    return core::config::mqtt_connection(config, tree.connection()).store_and_forward;
}

/// The first connection's journal is `history.sqlite`, as it was before connections were
/// several; another's is `history-{name}.sqlite`.
std::string journal_file(const core::config::Config& config, std::size_t connection) {
    if (connection == 0) return "history.sqlite";
    return "history-" +
           core::config::connection_name(core::config::mqtt_connection(config, connection)) +
           ".sqlite";
}

}  // namespace

StoreAndForwardModule::StoreAndForwardModule(std::unique_ptr<adapters::history::Journal> journal,
                                             const core::config::Config& config,
                                             const northbound::NorthboundParts& parts,
                                             northbound::json_tree::JsonTreeModule& tree)
    : store_(std::move(journal),
             StoreAndForwardOptions{.replay_rate = settings(config, tree).replay_rate,
                                    .fsync_interval = settings(config, tree).fsync_interval,
                                    .clock = &parts.clock},
             tree_link(tree.client()), tree.tree()),
      connection_(tree.connection()) {
    auto& client = tree.client();
    tree.tree().set_store_and_forward([&client] { return client.connected(); });
    tree.on_connected([this](core::MonoTime now) { store_.on_connected(now); });
    tree.take_acknowledgements([this](std::uint64_t token) {
        store_.on_acknowledged(token);
        return true;
    });
}

void StoreAndForwardModule::add_metrics(MetricsSources& sources) {
    stats_ = store_.stats();
    // A connection's entry is its tree's, made before this (make_northbounds puts each journal
    // after its tree).
    if (connection_ == 0) {
        sources.history = &*stats_;
    } else if (connection_ <= sources.more_connections.size()) {
        sources.more_connections[connection_ - 1].history = &*stats_;
    }
}

std::unique_ptr<StoreAndForwardModule> make_store_and_forward(
    const core::config::Config& config, const northbound::NorthboundParts& parts,
    northbound::json_tree::JsonTreeModule& tree) {
    const auto& section = settings(config, tree);
    if (!section.enabled) return nullptr;
    adapters::history::JournalOptions options;
    options.path =
        (std::filesystem::path(config.gateway.state_dir) / journal_file(config, tree.connection()))
            .string();
    options.max_bytes = section.max_mb << 20;
    options.clock = &parts.clock;
    std::unique_ptr<adapters::history::Journal> journal;
    try {
        std::filesystem::create_directories(config.gateway.state_dir);
        std::string set_aside;
        journal = adapters::history::Journal::open(options, set_aside);
        if (!set_aside.empty()) spdlog::warn("store and forward: {}", set_aside);
    } catch (const std::exception& error) {
        spdlog::error(
            "store and forward is off: the journal {} cannot be opened ({}); check that "
            "gateway.state_dir is writable by the service",
            options.path, error.what());
        return nullptr;
    }
    auto module = std::make_unique<StoreAndForwardModule>(std::move(journal), config, parts, tree);
    const auto stats = module->store().stats();
    spdlog::info("store and forward: journal {} ({} entries, bound {} MB)", options.path,
                 stats.journal.entries, section.max_mb);
    return module;
}

}  // namespace eip2mqtt::app::history
