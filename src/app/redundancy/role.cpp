// The roles a unit may have: a single unit's, and a hot-standby pair's (redundancy::Pair) as a
// module of the gateway, wired to the northbounds' connections, the JSON tree and the session of
// the Sparkplug edge node.

#include "eip2mqtt/app/redundancy/role.hpp"

#include <chrono>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_module.hpp"
#include "eip2mqtt/app/northbound/northbounds.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_module.hpp"
#include "eip2mqtt/app/redundancy/pair.hpp"

namespace eip2mqtt::app::redundancy {
namespace {

using namespace std::chrono_literals;

// How long a clean stop waits for the lease's queued publications before giving up.
constexpr auto stop_flush_timeout = 3s;

/// A single unit: it always leads, so it fences nothing and its sessions open at start.
class SingleUnit final : public Role {
public:
    MaySend may_send(MaySend) override { return nullptr; }
    ExchangesOptions exchanges_options() override { return {}; }
    std::unique_ptr<adapters::mqtt::Publisher> session_gate(adapters::mqtt::Publisher&) override {
        return nullptr;
    }
    bool sessions_follow_role() const override { return false; }
    void wire(RoleParts) override {}
};

/// The Sparkplug edge node's session, which only the leader holds; none without `sparkplug:`.
SessionHooks session_hooks(northbound::sparkplug::SparkplugModule* node) {
    if (node == nullptr) return {};
    return {[node](std::optional<std::uint8_t> heard) { node->open_session(heard); },
            [node] { node->end_session(); },
            [node] { return node->session_bd_seq(); },
            &node->node(),
            [node] { return node->node().may_send_data(); },
            [node] { return node->backlog(); }};
}

class PairRole final : public Role {
public:
    PairRole(boost::asio::any_io_executor loop, const core::Clock& clock) : pair_(loop, clock) {}

    MaySend may_send(MaySend fenced) override { return pair_.may_send(std::move(fenced)); }
    ExchangesOptions exchanges_options() override { return pair_.exchanges_options(); }
    std::unique_ptr<adapters::mqtt::Publisher> session_gate(
        adapters::mqtt::Publisher& inner) override {
        return pair_.leader_only(inner);
    }
    bool sessions_follow_role() const override { return true; }

    void wire(RoleParts parts) override {
        auto& tree = *parts.northbounds.tree;
        const auto backlog = [&tree] {
            const auto stats = tree.client().stats();
            return stats.queued + stats.in_flight;
        };
        pair_.wire({parts.config, backlog, tree.tree(), parts.writes, parts.exchanges, parts.north,
                    session_hooks(parts.northbounds.node), [&tree] { tree.republish(); }});
        // Before store and forward's journal entries: the pair's samples are its own tokens.
        if (pair_.hears_acknowledgements()) {
            tree.take_acknowledgements_first(
                [this](std::uint64_t token) { return pair_.on_acknowledged(token); });
        }
    }

    void start(core::MonoTime) override { pair_.start(); }
    void tick(const TickTimes& times) override {
        pair_.tick(times.now);
        pair_.tick_replay();
    }
    /// Nothing is produced any more: the lease goes, its will clearing the leader topic.
    void stop() override { pair_.stop(stop_flush_timeout); }
    void add_metrics(MetricsSources& sources) override {
        sources.pair_images = &pair_.image_counters();
        sources.pair_history = pair_.history_counters();
        sources.pair_writes = &pair_.write_counters();
        sources.role = &pair_;
    }

private:
    Pair pair_;
};

}  // namespace

std::unique_ptr<Role> make_role(const core::config::Config& config,
                                boost::asio::any_io_executor loop, const core::Clock& clock) {
    if (!config.redundancy.enabled()) return std::make_unique<SingleUnit>();
    return std::make_unique<PairRole>(std::move(loop), clock);
}

}  // namespace eip2mqtt::app::redundancy
