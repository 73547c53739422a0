#pragma once
/// The JSON topic tree (docs/mqtt-api.md): a retained topic per tag, `_status` and `_values` per
/// exchange, write results, the gateway's metrics; and writes on the `…/set` topics, decoded by
/// the WriteRouter and handed to the WriteHandler.
///
/// Threading: the loop only.

#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/history/history_sink.hpp"
#include "eip2mqtt/app/northbound/json_tree/write_router.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/plan/topic_rebase.hpp"

namespace eip2mqtt::app::northbound::json_tree {

/// How tag publications are made (from the `mqtt:` section).
struct PublishSettings {
    int qos = 1;
    bool retain = true;
    core::config::PayloadFormat format = core::config::PayloadFormat::json;
    bool batch = false;
    /// MQTT 5 user properties of data messages (mqtt.properties; none over MQTT 3.1.1).
    std::vector<core::config::MessageProperty> properties = {};

    friend bool operator==(const PublishSettings&, const PublishSettings&) = default;
};

struct JsonTreeOptions {
    PublishSettings publish;
    WriteRouterOptions writes;
    std::string metrics_topic;  ///< `{base}/_gateway/{id}/metrics`
    /// Whether it subscribes to the write topics (`mqtt.writes`).
    bool take_writes = true;
    /// A connection after the first: its name (its figures are the metrics topic's) and how
    /// its topics differ from the plans' (the tags' topics `_meta` names). Empty, identity:
    /// the first connection.
    std::string more_connection;
    core::plan::TopicRebase rebase = {};
};

/// The options of `config`'s `gateway:` section and of its MQTT connection `connection`
/// (core::config::mqtt_connection; the first by default).
JsonTreeOptions json_tree_options(const core::config::Config& config, std::size_t connection = 0);

/// How connection `connection` says the plans' topics: its base_topic for the first's.
core::plan::TopicRebase connection_rebase(const core::config::Config& config,
                                          std::size_t connection);

class JsonTree final : public Northbound, public history::HistorySink {
public:
    /// `mqtt` and `writes` must outlive the northbound.
    JsonTree(JsonTreeOptions options, adapters::mqtt::Publisher& mqtt, WriteHandler& writes);

    /// New settings (a reload), used from the next publication on: a gateway whose publish
    /// settings changed republishes its retained state.
    void set_options(JsonTreeOptions options);
    const JsonTreeOptions& options() const { return options_; }
    using AnswerHeard = std::function<void(const adapters::mqtt::Incoming& answer)>;
    using AnswerTopics = std::function<std::vector<std::string>()>;
    /// A unit of a pair (docs/redundancy.md): its connection also listens where writes are
    /// answered, `{set topic}/result` and the topics `topics` names (the response topics of
    /// the writes the standby left: redundancy::PairWrites), and hands what it hears there to
    /// `heard`. On the connection the writes come by, a write arrives before its answer, and
    /// the unit never hears its own answers (MQTT 5's no-local).
    void set_answer_listener(AnswerHeard heard, AnswerTopics topics);
    /// The topics of set_answer_listener changed: subscribed again.
    void listen_again() { subscribe(); }
    /// With store and forward, given the probe of its connection (the one the journal's
    /// LinkProbe asks): while the link is down, `_values` is not published (the
    /// journal has the samples and replays them on `_history`), and a reconnect's republish
    /// does not repeat `_values`, so that `_values` and `_history` carry each sample once.
    /// The tree asks its connection, never the journal, so the journal is the only one of the
    /// two that calls the other (it replays on the tree, its HistorySink).
    void set_store_and_forward(std::function<bool()> connected) {
        connected_ = std::move(connected);
        repeat_on_values_ = false;
    }
    using SampleToken = std::function<std::uint64_t(const SampleBatch& batch)>;
    /// With redundancy (docs/redundancy.md): `token` gives the acknowledgement token of the
    /// publication of each sample a batch names (SampleBatch::key): its `_values`, or without
    /// mqtt.batch the last of its tag topics, so that the leader learns which samples the broker
    /// has (app/redundancy/pair_history). And, as with store and forward, a republish (a
    /// takeover) does not repeat `_values`: the new leader's `_history` carries what it missed.
    void set_sample_tokens(SampleToken token) {
        sample_token_ = std::move(token);
        repeat_on_values_ = false;
    }

    /// A message on one of our subscriptions: a write on a `…/set` topic is decoded and handed
    /// to the WriteHandler, refused or not; anything else is ignored.
    void on_message(const adapters::mqtt::Incoming& message);

    /// The `set` topics follow `running` at once. The publications follow in slices, by
    /// publish_changes(): `retired_topics` (core::plan::diff_plans; a retired exchange's
    /// `_meta` among them) cleared, then each running exchange's `_meta` (json_tree_meta.hpp)
    /// published when new or changed, once republish_meta() has published them all. The
    /// previous call's publications must be done (changes_pending() false) or they are
    /// merged: its clears still made, its descriptions compared afresh.
    void exchanges_changed(const ExchangeSet& running,
                           std::span<const std::string> retired_topics) override;
    /// Makes the next publications exchanges_changed() left, taking at most `units`: one per
    /// cleared topic, one per description plus one per tag it describes (the formatting is the
    /// cost). Returns whether some are left.
    bool publish_changes(std::size_t units);
    bool changes_pending() const { return next_retired_ < retired_.size() || next_described_; }
    /// Makes every running exchange's `_meta` due (on each connect: the first, and a reconnect
    /// to a broker that may have lost its retained messages); publish_due_meta() sends them.
    void republish_meta();
    /// Publishes the next `meta_per_call` descriptions republish_meta() made due, in
    /// configuration order; called on every tick of the loop. Paced so that a plant's
    /// descriptions (megabytes) never queue all at once ahead of the live values.
    void publish_due_meta();
    static constexpr std::size_t meta_per_call = 16;
    void tag_samples(const SampleBatch& batch) override;
    void consumed_status(const ConsumedStatus& status) override;
    void produced_status(const core::plan::ExchangePlan& exchange,
                         const ProducedStatus& status) override;
    // exchange_state: nothing of its own, `_status` says it.
    void write_result(const WriteReply& reply, std::optional<std::string_view> error) override;
    void write_result_unsaved(const WriteReply& reply, std::string_view reason) override;
    void gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) override;
    /// `{exchange}/_history`: the `_values` shape, QoS 1, not retained, MQTT 5 user property
    /// `historical=true`.
    bool replay(const SampleBatch& batch, std::uint64_t ack_token) override;

private:
    /// Keeps the running exchanges in order; once connected, makes their `_meta` due for
    /// comparison by publish_changes().
    void describe(const ExchangeSet& running);
    /// publish_changes() for descriptions: returns the units it took.
    std::size_t describe_changed(std::size_t units);
    /// Whether `batch` goes on `_values` as well as on the tag topics.
    bool values_due(const SampleBatch& batch) const;
    /// The write topics' filters, and where writes are answered with an answer listener.
    void subscribe();
    /// A write result on the reply's topic, with its correlation data.
    void publish_result(const WriteReply& reply, std::string payload);

    JsonTreeOptions options_;
    adapters::mqtt::Publisher& mqtt_;
    WriteHandler& writes_;
    WriteRouter router_;
    AnswerHeard answer_heard_;
    AnswerTopics answer_topics_;
    /// With store and forward: whether the link is up (samples go live, not to the journal).
    std::function<bool()> connected_;
    /// A republish (every tag again) goes on `_values` too: neither store and forward nor a
    /// pair's takeover fills what `_values` missed on `_history`.
    bool repeat_on_values_ = true;
    SampleToken sample_token_;  ///< with a pair
    /// A digest of each running exchange's `_meta` payload as last published, by topic, so that
    /// a reload publishes only the descriptions that changed without the gateway holding every
    /// payload (tens of bytes a tag: megabytes for 100,000 tags). Two different payloads with
    /// one 64-bit digest would leave a change unpublished; at the handful of reloads a gateway
    /// sees, that chance is nil.
    std::unordered_map<std::string, std::size_t> meta_digests_;
    std::vector<const core::plan::ExchangePlan*> described_;  ///< the running, in order
    /// Retained topics to clear (exchanges_changed), the next at next_retired_.
    std::vector<std::string> retired_;
    std::size_t next_retired_ = 0;
    /// The next running exchange whose `_meta` publish_changes() compares, into described_;
    /// none when none is left. The digests of those compared so far, for meta_digests_.
    std::optional<std::size_t> next_described_;
    std::unordered_map<std::string, std::size_t> described_digests_;
    /// republish_meta() ran: changes are published from then on.
    bool announced_ = false;
    /// The next description due, into described_; none when none is due.
    std::optional<std::size_t> next_due_meta_;
    /// Every tag publication is filled in here; the publisher takes its content and leaves
    /// spare buffers (Client::publish), so the data path does not allocate.
    adapters::mqtt::Message message_;
};

}  // namespace eip2mqtt::app::northbound::json_tree
