#include "eip2mqtt/app/redundancy/role_metrics.hpp"

#include <nlohmann/json.hpp>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/json_tree/counter_json.hpp"
#include "eip2mqtt/app/redundancy/pair_counters.hpp"

namespace eip2mqtt::app::redundancy {

void add_role_metrics(nlohmann::json& metrics, const MetricsSources& sources) {
    if (!sources.pair_images) return;
    northbound::json_tree::add_counter_set(
        metrics["pair"], pair_counter_fields,
        PairCounters{*sources.pair_images, sources.datagrams.produced_heard,
                     sources.pair_history ? *sources.pair_history : PairHistoryCounters{},
                     sources.mqtt.discarded,
                     sources.pair_writes ? *sources.pair_writes : PairWriteCounters{}});
}

}  // namespace eip2mqtt::app::redundancy
