#pragma once
/// The Sparkplug B edge node as a module of the gateway (docs/sparkplug.md): the node on a
/// connection of its own, whose will is its NDEATH, and its replay of store and forward's
/// journal once it is born. Its session opens when the gateway starts, or, when the role says
/// so (redundancy::Role::sessions_follow_role), when this unit takes the role: the one edge
/// node of several units is held by one of them at a time.
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>

#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/adapters/state/bd_seq_file.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/app/northbound/northbounds.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_node.hpp"

namespace eip2mqtt::app::history {
class StoreAndForward;
}

namespace eip2mqtt::app::northbound::sparkplug {

class SparkplugModule final : public Module {
public:
    /// `history`, when not null, replays on the node's connection too. Throws std::exception
    /// when the connection's options cannot be made (an unreadable password file).
    SparkplugModule(const core::config::Config& config, const NorthboundParts& parts,
                    history::StoreAndForward* history);

    SparkplugNode& node() { return *node_; }

    /// Opens the node's session, with a bdSeq other than `heard_bd_seq` (the last one another
    /// unit used), and connects with its NDEATH as the will.
    void open_session(std::optional<std::uint8_t> heard_bd_seq);
    /// Ends it: what waited dropped, its NDEATH said last.
    void end_session();
    std::optional<std::uint8_t> session_bd_seq() const { return node_->session_bd_seq(); }
    /// The publications its connection holds, queued and in flight.
    std::uint64_t backlog() const;

    /// Connects, unless its session follows the role.
    void start(core::MonoTime now) override;
    /// The node's NDEATH after its last data.
    void stop() override;
    void tick(const TickTimes& times) override;
    void add_metrics(MetricsSources& sources) override;
    /// The connection's buffer settings.
    void apply(const core::config::Config& next) override;

private:
    /// Runs `event` (the connection, a message on it, a tick); once the node is born by it,
    /// its replay of history starts.
    void on_event(bool connection, const std::function<void()>& event);
    void add_history();
    /// The node's will for the next CONNECT; its bdSeq kept in the state directory.
    adapters::mqtt::Message next_will();

    const core::Clock& clock_;
    history::StoreAndForward* history_;
    bool opens_at_start_;
    std::unique_ptr<adapters::mqtt::Client> client_;
    /// Between the node and its connection when the session follows the role.
    std::unique_ptr<adapters::mqtt::Publisher> gate_;
    std::unique_ptr<SparkplugNode> node_;
    adapters::state::BdSeqFile bd_seq_file_;
    std::optional<std::uint8_t> kept_bd_seq_;  ///< what bd_seq_file_ holds
};

/// The file of the state directory that keeps the node's bdSeq across restarts.
inline constexpr std::string_view bd_seq_file_name = "sparkplug-bdseq";

/// The edge node of `config`'s `sparkplug:`, else null.
std::unique_ptr<SparkplugModule> make_sparkplug(const core::config::Config& config,
                                                const NorthboundParts& parts,
                                                history::StoreAndForward* history);

}  // namespace eip2mqtt::app::northbound::sparkplug
