#pragma once
/// The JSON topic tree as a module of the gateway (docs/mqtt-api.md): the tree on one MQTT
/// connection (the gateway's main one, or one more of a list), whose will is the gateway's
/// `offline` there, and the pacing of its `_meta`
/// topics. On every connection the exchanges' retained state is said again, then whoever
/// listens for the connection (store and forward's replay) goes on behind it. The
/// acknowledgements of the connection go to whoever takes the token (a takeover's samples, a
/// journal entry).
///
/// Threading: the loop only.

#include <boost/asio/any_io_executor.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/app/module.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"
#include "eip2mqtt/app/northbound/json_tree/rebased_publisher.hpp"
#include "eip2mqtt/app/northbound/northbounds.hpp"

namespace eip2mqtt::app::northbound::json_tree {

class JsonTreeModule final : public Module {
public:
    /// Whether it took an acknowledged token.
    using Taker = std::function<bool(std::uint64_t token)>;

    /// The tree on MQTT connection `connection` (core::config::mqtt_connection: 0 is the
    /// first, the gateway's main one). Throws std::exception when the connection's options
    /// cannot be made (an unreadable password file).
    JsonTreeModule(const core::config::Config& config, const NorthboundParts& parts,
                   std::size_t connection = 0);

    adapters::mqtt::Client& client() { return *client_; }
    const adapters::mqtt::Client& client() const { return *client_; }
    std::size_t connection() const { return connection_; }
    JsonTree& tree() { return tree_; }
    /// Every running exchange's retained state again, and the `_meta` topics.
    void republish();
    /// Offered the connection's acknowledgements, after those given before (first: before).
    void take_acknowledgements(Taker taker) { takers_.push_back(std::move(taker)); }
    void take_acknowledgements_first(Taker taker) {
        takers_.insert(takers_.begin(), std::move(taker));
    }
    /// How the exchanges say their state again for this tree alone (FanOut::excluding): `run`
    /// with the other connections' trees kept out. Unset: to every northbound.
    using RepublishScope = std::function<void(const std::function<void()>& run)>;
    void set_republish_scope(RepublishScope scope) { republish_scope_ = std::move(scope); }
    /// Called on each connection, once the retained state was said again.
    void on_connected(std::function<void(core::MonoTime now)> listener) {
        connected_.push_back(std::move(listener));
    }

    void start(core::MonoTime now) override;
    void tick(const TickTimes& times) override;
    /// The retained topics a reload had yet to clear, then the queue flushed and `offline`.
    void stop() override;
    void apply(const core::config::Config& next) override;
    void applied() override;
    bool changes_pending() const override { return tree_.changes_pending(); }
    void publish_changes(std::size_t units) override { tree_.publish_changes(units); }
    std::optional<core::config::PublishQueueRoom> queue_room() const override;
    void add_metrics(MetricsSources& sources) override;

private:
    void connected();
    void acknowledged(std::uint64_t token);

    const core::Clock& clock_;
    Exchanges& exchanges_;
    std::size_t connection_;
    std::string name_;
    std::size_t buffer_max_messages_;
    std::unique_ptr<adapters::mqtt::Client> client_;
    std::unique_ptr<RebasedPublisher> rebased_;  ///< a connection with a base_topic of its own
    JsonTree tree_;
    std::vector<Taker> takers_;
    std::vector<std::function<void(core::MonoTime)>> connected_;
    RepublishScope republish_scope_;
    /// A reload changed how tags are published: their state goes again once it is applied.
    bool republish_due_ = false;
};

}  // namespace eip2mqtt::app::northbound::json_tree
