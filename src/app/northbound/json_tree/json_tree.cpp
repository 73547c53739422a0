#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_meta.hpp"
#include "eip2mqtt/app/northbound/json_tree/json_tree_payload.hpp"
#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::app::northbound::json_tree {

JsonTreeOptions json_tree_options(const core::config::Config& config, std::size_t connection) {
    const auto& mqtt = core::config::mqtt_connection(config, connection);
    // Kepware's consumers read one message per exchange: its profile publishes `_values`.
    const bool batch = mqtt.batch || mqtt.payload == core::config::PayloadFormat::kepware;
    auto properties =
        mqtt.version == 5 ? mqtt.properties : std::vector<core::config::MessageProperty>{};
    return {{mqtt.qos, mqtt.retain, mqtt.payload, batch, std::move(properties)},
            {mqtt.base_topic, mqtt.allow_response_topics_under_base, mqtt.payload},
            mqtt.base_topic + "/_gateway/" + config.gateway.id + "/metrics",
            core::config::takes_writes(mqtt, connection),
            connection == 0 ? std::string() : core::config::connection_name(mqtt),
            connection_rebase(config, connection)};
}

core::plan::TopicRebase connection_rebase(const core::config::Config& config,
                                          std::size_t connection) {
    return {config.mqtt.base_topic, core::config::mqtt_connection(config, connection).base_topic};
}

JsonTree::JsonTree(JsonTreeOptions options, adapters::mqtt::Publisher& mqtt, WriteHandler& writes)
    : options_(std::move(options)), mqtt_(mqtt), writes_(writes), router_(options_.writes) {}

void JsonTree::set_options(JsonTreeOptions options) {
    options_ = std::move(options);
    router_.set_options(options_.writes);
}

void JsonTree::exchanges_changed(const ExchangeSet& running,
                                 std::span<const std::string> retired_topics) {
    // No subscriber may keep reading a tag that no longer exists (publish_changes).
    if (next_retired_ == retired_.size()) {
        retired_.clear();
        next_retired_ = 0;
    }
    retired_.insert(retired_.end(), retired_topics.begin(), retired_topics.end());
    describe(running);
    router_.clear();
    for (const auto* plan : running.consumed) router_.add(*plan);
    for (const auto* plan : running.produced) router_.add(*plan);
    subscribe();
}

void JsonTree::set_answer_listener(AnswerHeard heard, AnswerTopics topics) {
    answer_heard_ = std::move(heard);
    answer_topics_ = std::move(topics);
    subscribe();
}

void JsonTree::subscribe() {
    auto filters = options_.take_writes ? router_.subscriptions() : std::vector<std::string>{};
    if (answer_heard_) {
        // `{base}/+/set` and the like: `{set topic}/result` lies under each one's `/result`.
        const auto writes = filters.size();
        filters.reserve(2 * writes);
        for (std::size_t i = 0; i < writes; ++i) filters.push_back(filters[i] + "/result");
        if (answer_topics_) {
            auto topics = answer_topics_();
            filters.insert(filters.end(), topics.begin(), topics.end());
        }
    }
    mqtt_.set_subscriptions(std::move(filters));
}

void JsonTree::describe(const ExchangeSet& running) {
    described_.clear();
    for (const auto* plans : {&running.consumed, &running.produced}) {
        described_.insert(described_.end(), plans->begin(), plans->end());
    }
    // The running set changed under a republish in progress: it starts again from the first.
    if (next_due_meta_) next_due_meta_ = 0;
    // Before the first connection nothing has reached the broker: republish_meta() on
    // connecting publishes every description (and notes its digest), so none is formatted here.
    if (!announced_) return;
    next_described_ = 0;
    described_digests_.clear();
}

bool JsonTree::publish_changes(std::size_t units) {
    std::size_t used = 0;
    for (; used < units && next_retired_ < retired_.size(); ++used, ++next_retired_) {
        mqtt_.publish({std::move(retired_[next_retired_]), "", options_.publish.qos, true, true});
    }
    if (next_retired_ == retired_.size()) {
        std::vector<std::string>().swap(retired_);  // a plant's topics: megabytes
        next_retired_ = 0;
        used += describe_changed(units - used);
    }
    return changes_pending();
}

std::size_t JsonTree::describe_changed(std::size_t units) {
    std::size_t used = 0;
    if (!next_described_) return used;
    auto& next = *next_described_;
    // A kept or unchanged exchange's `_meta` stays as the broker has it.
    for (; used < units && next < described_.size(); ++next) {
        const auto& plan = *described_[next];
        auto payload = format_meta_payload(plan, options_.rebase);
        const auto digest = std::hash<std::string>{}(payload);
        const auto old = meta_digests_.find(plan.meta_topic);
        if (old == meta_digests_.end() || old->second != digest) {
            mqtt_.publish({plan.meta_topic, std::move(payload), options_.publish.qos, true, true});
        }
        described_digests_.emplace(plan.meta_topic, digest);
        used += 1 + plan.tags.size();
    }
    if (next >= described_.size()) {
        meta_digests_ = std::move(described_digests_);
        described_digests_.clear();
        next_described_.reset();
    }
    return used;
}

void JsonTree::republish_meta() {
    announced_ = true;
    next_due_meta_ = 0;
}

void JsonTree::publish_due_meta() {
    if (!next_due_meta_) return;
    auto& next = *next_due_meta_;
    for (std::size_t sent = 0; sent < meta_per_call && next < described_.size(); ++sent, ++next) {
        const auto& plan = *described_[next];
        auto payload = format_meta_payload(plan, options_.rebase);
        meta_digests_[plan.meta_topic] = std::hash<std::string>{}(payload);
        mqtt_.publish({plan.meta_topic, std::move(payload), options_.publish.qos, true, true});
    }
    if (next >= described_.size()) next_due_meta_.reset();
}

bool JsonTree::values_due(const SampleBatch& batch) const {
    // `_values` carries what consumed datagrams bring, not the echo of produced ones.
    if (!options_.publish.batch || batch.samples.empty() ||
        batch.exchange.spec.direction != core::plan::Direction::consume) {
        return false;
    }
    if (batch.all_tags && !repeat_on_values_) return false;
    // While store and forward's link is down, the journal has the sample.
    return !connected_ || connected_();
}

void JsonTree::tag_samples(const SampleBatch& batch) {
    const auto& settings = options_.publish;
    const auto& plan = batch.exchange;
    const bool values = values_due(batch);
    // The publication whose acknowledgement tells the sample token's owner that the broker has
    // the sample: its `_values`, or without mqtt.batch its last tag topic.
    const bool acknowledged = sample_token_ && batch.key && (values || !settings.batch);
    const auto token = acknowledged && !batch.samples.empty() ? sample_token_(batch) : 0;
    for (const auto& sample : batch.samples) {
        // Filled in place and handed over: the publisher gives back buffers of an earlier
        // publication, so a tag's publication allocates nothing here.
        plan.tag_topic_into(plan.tags[sample.tag], message_.topic);
        format_tag_payload(message_.payload, plan.spec.name, plan.tags[sample.tag].spec,
                           sample.value, batch.quality, batch.timestamp_ms, settings.format);
        message_.qos = settings.qos;
        message_.retain = settings.retain;
        message_.live = true;
        message_.text = settings.format == core::config::PayloadFormat::value;
        add_data_properties(message_, settings.properties, plan, &plan.tags[sample.tag].spec,
                            batch.quality, batch.timestamp_ms);
        if (!values && &sample == &batch.samples.back()) message_.ack_token = token;
        mqtt_.publish(std::move(message_));  // leaves message_ blank (Publisher)
    }
    if (values) {
        message_.topic = plan.values_topic;
        format_values_payload(message_.payload, batch, settings.format);
        message_.qos = settings.qos;
        message_.live = true;
        add_data_properties(message_, settings.properties, plan, nullptr, batch.quality,
                            batch.timestamp_ms);
        message_.coalesce = false;
        message_.batch_lane = true;
        message_.ack_token = token;
        mqtt_.publish(std::move(message_));
    }
}

bool JsonTree::replay(const SampleBatch& batch, std::uint64_t ack_token) {
    message_.topic.assign(batch.exchange.topic).append("/_history");
    format_values_payload(message_.payload, batch);
    message_.qos = 1;  // an entry leaves the journal on its PUBACK
    add_data_properties(message_, options_.publish.properties, batch.exchange, nullptr,
                        batch.quality, batch.timestamp_ms);
    message_.coalesce = false;
    message_.historical = true;
    message_.ack_token = ack_token;
    mqtt_.publish(std::move(message_));
    return true;
}

void JsonTree::consumed_status(const ConsumedStatus& status) {
    mqtt_.publish({status.exchange.status_topic, format_status_payload(status),
                   options_.publish.qos, true, true});
}

void JsonTree::produced_status(const core::plan::ExchangePlan& exchange,
                               const ProducedStatus& status) {
    mqtt_.publish({exchange.status_topic, format_produced_status_payload(status),
                   options_.publish.qos, true, true});
}

void JsonTree::write_result(const WriteReply& reply, std::optional<std::string_view> error) {
    publish_result(reply, format_write_result(error));
}

void JsonTree::write_result_unsaved(const WriteReply& reply, std::string_view reason) {
    publish_result(reply, format_write_result_unsaved(reason));
}

void JsonTree::publish_result(const WriteReply& reply, std::string payload) {
    // Each result must be delivered: never coalesced with another on the same topic.
    if (reply.topic.empty()) return;  // nowhere a broker accepts (WriteRouter::route)
    adapters::mqtt::Message result{reply.topic, std::move(payload), 1, false, false};
    result.correlation_data = reply.correlation_data;
    mqtt_.publish(std::move(result));
}

void JsonTree::gateway_metrics(const MetricsSources& sources, std::chrono::seconds uptime) {
    if (!options_.more_connection.empty()) {
        // Another connection's topic tells of that connection: its broker, its queue.
        for (const auto& more : sources.more_connections) {
            if (more.name != options_.more_connection) continue;
            auto own = sources;
            own.mqtt = more.mqtt;
            own.history = more.history;
            own.mqtt_name = more.name;
            return mqtt_.publish(
                {options_.metrics_topic, metrics_json(own, uptime), 0, false, true});
        }
    }
    mqtt_.publish({options_.metrics_topic, metrics_json(sources, uptime), 0, false, true});
}

void JsonTree::on_message(const adapters::mqtt::Incoming& message) {
    auto decision = options_.take_writes ? router_.route(message) : std::nullopt;
    if (!decision) {
        if (answer_heard_) answer_heard_(message);  // no write: maybe an answer to one
        return;
    }
    WriteRequest request{
        std::move(decision->reply), message.topic, std::move(decision->outcome), {}};
    request.reply.origin = this;
    if (!decision->response_topic_problem.empty()) {
        request.log_detail = " (the response topic " + core::printable(message.response_topic) +
                             " " + decision->response_topic_problem + "; answered on " +
                             request.reply.topic + ")";
    }
    writes_.on_write(std::move(request));
}

}  // namespace eip2mqtt::app::northbound::json_tree
