#pragma once
/// One consumed exchange at run time: its ConsumedExchange state, the report-by-exception filter
/// of each tag, and the publications they lead to (tag topics, `_status`, `_values`).
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/exchange/arrival_stats.hpp"
#include "eip2mqtt/core/exchange/consumed_exchange.hpp"
#include "eip2mqtt/core/exchange/producer_clock.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/quality/report_filter.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

/// How tag publications are made (from the `mqtt:` section).
struct PublishSettings {
    int qos = 1;
    bool retain = true;
    core::config::PayloadFormat format = core::config::PayloadFormat::json;
    bool batch = false;

    friend bool operator==(const PublishSettings&, const PublishSettings&) = default;
};

/// Where publications go (the MQTT client's queue, or a recorder in tests). It takes the
/// message's content and leaves it blank (Message::clear()), possibly with the buffers of an
/// earlier one, to be filled again.
using PublishSink = std::function<void(adapters::mqtt::Message&&)>;

class ExchangeConsumer {
public:
    ExchangeConsumer(core::plan::ExchangePlan plan, PublishSettings settings, PublishSink sink);

    /// A datagram whose key matched this exchange.
    core::exchange::ConsumeOutcome on_datagram(const core::wire::Datagram& datagram,
                                               core::MonoTime now, core::WallTime wall);

    /// Timeout, refresh and throttled `_status`; `refresh_scan` also checks refresh_s (the
    /// caller asks for it about once a second: refresh is counted in seconds).
    void on_tick(core::MonoTime now, core::WallTime wall, bool refresh_scan);

    /// Publishes every tag and `_status` again (after a reconnect: brokers lose retained state).
    void republish(core::MonoTime now, core::WallTime wall);

    const core::plan::ExchangePlan& plan() const { return plan_; }
    const PublishSettings& settings() const { return settings_; }
    const core::exchange::ConsumedExchange& exchange() const { return exchange_; }
    const core::exchange::ProducerClock& clock() const { return clock_; }
    /// Inter-arrival period and jitter of accepted datagrams.
    const core::exchange::ArrivalStats& arrivals() const { return arrivals_; }
    /// A datagram of this exchange from an address other than its `source`.
    /// ConsumedExchange::accepts_source: false (and counted) for a datagram to drop.
    bool accepts_source(std::uint32_t address) { return exchange_.accepts_source(address); }
    std::uint64_t wrong_source() const { return exchange_.counters().wrong_source; }

private:
    void publish_tags(core::MonoTime now, bool force);
    void publish_status(core::MonoTime now, core::WallTime wall);
    /// The timestamp of the accepted datagram's tags (ProducerClock), logging a clock change.
    std::int64_t sample_time(core::WallTime wall);
    void log_clock(bool first);

    core::plan::ExchangePlan plan_;
    PublishSettings settings_;
    PublishSink sink_;
    core::exchange::ConsumedExchange exchange_;
    std::vector<core::quality::ReportFilter> filters_;  ///< one per tag of plan_.tags
    /// With mqtt.batch: `"name":` of each tag of plan_.tags, escaped once for `_values`.
    std::vector<std::string> batch_keys_;
    core::exchange::ArrivalStats arrivals_;
    core::exchange::ProducerClock clock_;
    bool clock_seen_ = false;                   ///< a datagram was accepted since start
    std::int64_t timestamp_ms_ = 0;             ///< of the values the tags publish
    std::optional<std::int64_t> last_seen_ms_;  ///< wall time of the last accepted datagram
    std::optional<core::MonoTime> last_status_at_;
    std::uint64_t last_status_received_ = 0;
    bool status_dirty_ = true;
    /// Every tag publication is filled in here; the sink (the MQTT client) takes its content
    /// and leaves spare buffers (Client::publish), so the data path does not allocate.
    adapters::mqtt::Message message_;
};

}  // namespace eip2mqtt::app
