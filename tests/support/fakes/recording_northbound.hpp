#pragma once
// A fake Northbound: it keeps every event, copied, in the order they came, so that a test reads
// what an exchange reported without any protocol in between.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/app/northbound/northbound.hpp"

namespace eip2mqtt::test {

class RecordingNorthbound final : public app::Northbound {
public:
    struct Batch {
        std::string exchange;
        core::quality::Quality quality;
        std::int64_t timestamp_ms;
        bool all_tags;
        std::vector<app::TagSample> samples;
        std::optional<core::redundancy::SampleKey> key;
    };
    struct Result {
        std::string topic;
        std::optional<std::string> error;
    };
    struct State {
        std::string exchange;
        core::exchange::ConsumeState state;
    };

    void exchanges_changed(const app::ExchangeSet& running,
                           std::span<const std::string> retired_topics) override {
        consumed = running.consumed.size();
        produced = running.produced.size();
        retired.assign(retired_topics.begin(), retired_topics.end());
        events.push_back("exchanges");
    }
    void tag_samples(const app::SampleBatch& batch) override {
        batches.push_back({batch.exchange.spec.name,
                           batch.quality,
                           batch.timestamp_ms,
                           batch.all_tags,
                           {batch.samples.begin(), batch.samples.end()},
                           batch.key});
        events.push_back("samples");
    }
    void consumed_status(const app::ConsumedStatus& status) override {
        consumed_statuses.push_back(status.state.counters());
        events.push_back("status");
    }
    void produced_status(const core::plan::ExchangePlan&,
                         const app::ProducedStatus& status) override {
        produced_statuses.push_back(status);
        events.push_back("status");
    }
    void exchange_state(const core::plan::ExchangePlan& exchange,
                        core::exchange::ConsumeState state) override {
        states.push_back({exchange.spec.name, state});
        events.push_back("state");
    }
    void write_result(const app::WriteReply& reply,
                      std::optional<std::string_view> error) override {
        results.push_back({reply.topic, error ? std::optional<std::string>(*error) : std::nullopt});
        events.push_back("result");
    }
    void gateway_metrics(const app::MetricsSources&, std::chrono::seconds) override {
        events.push_back("metrics");
    }

    std::vector<std::string> events;  ///< the kind of each event, in order
    std::vector<Batch> batches;
    std::vector<core::exchange::ConsumeCounters> consumed_statuses;
    std::vector<app::ProducedStatus> produced_statuses;
    std::vector<State> states;
    std::vector<Result> results;
    std::size_t consumed = 0;
    std::size_t produced = 0;
    std::vector<std::string> retired;
};

}  // namespace eip2mqtt::test
