#pragma once
/// `{exchange}/_meta` (docs/mqtt-api.md, docs/schema/meta.json): what a consumer of the JSON
/// tree needs to know of an exchange and its tags without reading the configuration (a
/// dashboard, a historian, an MES): each tag's type, address, unit, description, writability,
/// limits and deadband, and the exchange's direction, ids, length and period. Sparkplug
/// consumers learn the same from the births. Retained; published when the exchange starts and
/// whenever a reload changes it, cleared when the exchange goes.
///
/// Threading: any; pure functions of the plan.

#include <string>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/topic_rebase.hpp"

namespace eip2mqtt::app::northbound::json_tree {

/// The payload of `plan.meta_topic`: one JSON object, tags in configuration order, keyed by name;
/// each tag's topic as the connection says it (`rebase`).
std::string format_meta_payload(const core::plan::ExchangePlan& plan,
                                const core::plan::TopicRebase& rebase = {});

}  // namespace eip2mqtt::app::northbound::json_tree
