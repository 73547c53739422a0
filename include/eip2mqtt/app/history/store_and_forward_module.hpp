#pragma once
/// Store and forward as a module of the gateway (docs/store-and-forward.md): the journal under
/// gateway.state_dir, fed by the exchanges through the fan-out while the JSON tree's
/// connection is down, replayed on `_history` behind the retained state once it is back; and on
/// the Sparkplug node's connection as well, once the node is born (SparkplugModule adds it).
///
/// Threading: the loop only.

#include <memory>
#include <optional>

#include "eip2mqtt/app/history/store_and_forward.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/app/northbound/northbounds.hpp"

namespace eip2mqtt::app::history {

class StoreAndForwardModule final : public Module {
public:
    /// Joins the JSON tree's connection (its replay, its acknowledgements); the fan-out is
    /// joined by its maker (northbound::make_northbounds).
    StoreAndForwardModule(std::unique_ptr<adapters::history::Journal> journal,
                          const core::config::Config& config,
                          const northbound::NorthboundParts& parts,
                          northbound::json_tree::JsonTreeModule& tree);

    StoreAndForward& store() { return store_; }

    /// Before the metrics: figures showing a datagram accepted then show it journaled.
    void tick(const TickTimes& times) override { store_.on_tick(times.now); }
    void add_metrics(MetricsSources& sources) override;

private:
    StoreAndForward store_;
    std::size_t connection_;             ///< the MQTT connection whose samples it keeps
    std::optional<HistoryStats> stats_;  ///< the last figures add_metrics lent
};

/// Store and forward of `tree`'s connection with its `store_and_forward`, else null: a journal
/// per connection (`history.sqlite` for the first, `history-{name}.sqlite` for the others). A
/// journal that cannot be opened is logged and the gateway runs without it (null too).
std::unique_ptr<StoreAndForwardModule> make_store_and_forward(
    const core::config::Config& config, const northbound::NorthboundParts& parts,
    northbound::json_tree::JsonTreeModule& tree);

}  // namespace eip2mqtt::app::history
