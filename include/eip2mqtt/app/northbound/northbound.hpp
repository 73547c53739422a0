#pragma once
/// The seam between the exchanges and the protocols that carry their data north.
/// Consumers and producers report domain events here (tag samples, exchange status, an exchange
/// going up or down, write results) and know neither MQTT nor JSON; each protocol implements
/// Northbound in a folder of its own: the JSON topic tree in app/northbound/json_tree/, the
/// Sparkplug node in app/northbound/sparkplug/. FanOut hands every event to several at once.
/// Writes come back the other way: a northbound decodes what its clients send into one
/// WriteRequest and hands it to a WriteHandler (the Gateway), whatever the protocol.
///
/// Threading: the loop only. An event borrows its data for the call.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "eip2mqtt/app/exchanges/write_reply.hpp"
#include "eip2mqtt/core/exchange/consumed_exchange.hpp"
#include "eip2mqtt/core/exchange/produce_counters.hpp"
#include "eip2mqtt/core/exchange/remote_producer_clock.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_sample.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/quality/quality.hpp"
#include "eip2mqtt/core/redundancy/sample_key.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::app {

struct MetricsSources;

/// The running exchanges.
struct ExchangeSet {
    std::vector<const core::plan::ExchangePlan*> consumed;
    std::vector<const core::plan::ExchangePlan*> produced;
};

/// One tag's value in a SampleBatch.
using TagSample = core::plan::TagSample;

/// Where an exchange gathers the samples of the SampleBatch it is about to report, empty: one
/// buffer per thread, shared by every consumed and produced exchange of the loop, since the
/// Northbound reads a batch before tag_samples returns. Its capacity follows the largest
/// exchange, so the data path does not allocate. A buffer per exchange, sized for every tag,
/// cost resident memory in proportion to the tags configured (docs/decisions/0001).
inline std::vector<TagSample>& sample_buffer() {
    thread_local std::vector<TagSample> samples;
    samples.clear();
    return samples;
}

/// The tags of one exchange to report at one time: those a datagram changed (after deadband
/// and refresh), all of them marked stale or bad, the values a produced datagram carried, or
/// every tag again after a (re)connect. They share one quality and one timestamp.
struct SampleBatch {
    const core::plan::ExchangePlan& exchange;
    core::quality::Quality quality;
    std::int64_t timestamp_ms;  ///< chosen by the exchange's clock rules (RemoteProducerClock)
    bool all_tags;              ///< every tag of the exchange, not only the changed ones
    std::span<const TagSample> samples;
    /// A consumed exchange's sample by its datagram, alike on both units of a pair
    /// (core/redundancy/sample_key.hpp): that of an accepted datagram, or of a change of
    /// quality after it. None for a refresh or a republish, which repeat a sample, and for a
    /// produced exchange.
    std::optional<core::redundancy::SampleKey> key = std::nullopt;
};

/// A consumed exchange's counters and clock, reported on every state change and at most once a
/// second while its counters move.
struct ConsumedStatus {
    const core::plan::ExchangePlan& exchange;
    const core::exchange::ConsumedExchange& state;
    std::optional<std::int64_t> last_seen_ms;  ///< wall time of the last accepted datagram
    const core::exchange::RemoteProducerClock& clock;
};

/// A produced exchange's counters and state.
struct ProducedStatus {
    bool paused = false;           ///< sends fail
    std::uint16_t request_id = 0;  ///< of the next datagram
    core::exchange::ProduceCounters counters;
    std::uint64_t writes_pending = 0;
    /// The image file holds the image being produced (or a newer one, saved ahead of it).
    bool saved = true;
    std::string_view save_error;  ///< why the last save failed; empty once one succeeds
};

/// Names a running produced exchange: its plan, which stays at one address for the producer's
/// life (ExchangeSet::produced lists them). A reload that changes the exchange makes a new one.
using ProducerHandle = const core::plan::ExchangePlan*;

/// Validated writes for one produced exchange, applied together in one datagram.
struct ExchangeWrite {
    ProducerHandle producer = nullptr;
    std::vector<core::write::TagWrite> writes;
};

/// A write as a northbound decoded it: what to apply, or why it is refused before it reaches
/// an exchange. Either way its result goes back to `reply.origin`.
struct WriteRequest {
    WriteReply reply;
    std::string target;  ///< what it addresses, for the log (a topic, a device)
    std::variant<ExchangeWrite, core::write::WriteRejection> outcome;
    std::string log_detail;  ///< appended to the log line of a refusal
};

/// Every event has a default that ignores it: a northbound overrides the ones it has a use for
/// (the journal only samples, the command responder only write results).
class Northbound {
public:
    virtual ~Northbound() = default;

    /// The running exchanges, at start and after each reload. `retired_topics` are the retained
    /// topics of the JSON tree that no running exchange uses any more (core::plan::diff_plans).
    /// A kept exchange has the same plan object as before; the exchanges a reload stops are
    /// destroyed only after this call, so no new plan has the address of one of them.
    virtual void exchanges_changed(const ExchangeSet& /*running*/,
                                   std::span<const std::string> /*retired_topics*/) {}
    virtual void tag_samples(const SampleBatch& /*batch*/) {}
    virtual void consumed_status(const ConsumedStatus& /*status*/) {}
    virtual void produced_status(const core::plan::ExchangePlan& /*exchange*/,
                                 const ProducedStatus& /*status*/) {}
    /// A consumed exchange changed state: up is `ok`, every other state is down.
    virtual void exchange_state(const core::plan::ExchangePlan& /*exchange*/,
                                core::exchange::ConsumeState /*state*/) {}
    /// The result of a write that came from this northbound (`reply.origin`): nullopt when it
    /// was applied and carried by a sent datagram, else why not.
    virtual void write_result(const WriteReply& /*reply*/,
                              std::optional<std::string_view> /*error*/) {}
    /// The result of a write that was applied and carried by a sent datagram, but whose image
    /// could not be saved (`reason`): a restart before the next successful save would produce
    /// the image from before it.
    virtual void write_result_unsaved(const WriteReply& /*reply*/, std::string_view /*reason*/) {}
    /// The gateway's counters, every mqtt.metrics_interval.
    virtual void gateway_metrics(const MetricsSources& /*sources*/,
                                 std::chrono::seconds /*uptime*/) {}
};

/// Where northbounds hand the writes they decode.
class WriteHandler {
public:
    virtual ~WriteHandler() = default;
    virtual void on_write(WriteRequest&& request) = 0;
};

}  // namespace eip2mqtt::app
