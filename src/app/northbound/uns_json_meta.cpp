#include "eip2mqtt/app/northbound/uns_json_meta.hpp"

#include <nlohmann/json.hpp>

#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app::northbound {
namespace {

using Json = nlohmann::ordered_json;
using core::plan::Direction;

/// A setting a tag may lack: null rather than left out, so that every tag has every key.
template <class T>
Json or_null(const std::optional<T>& value) {
    return value ? Json(*value) : Json(nullptr);
}

Json text_or_null(const std::string& text) { return text.empty() ? Json(nullptr) : Json(text); }

Json tag_meta(const core::plan::TagPlan& tag) {
    const auto& spec = tag.spec;
    return {
        {"type", std::string(core::plan::to_string(spec.type))},
        {"address", core::plan::to_string(spec.address)},
        {"unit", text_or_null(spec.unit())},
        {"description", text_or_null(spec.description())},
        {"writable", spec.writable},
        {"min", or_null(spec.min())},
        {"max", or_null(spec.max())},
        {"deadband", spec.deadband},
    };
}

}  // namespace

std::string format_meta_payload(const core::plan::ExchangePlan& plan) {
    const auto& spec = plan.spec;
    const bool consumed = spec.direction == Direction::consume;
    Json meta = {
        {"exchange", spec.name},
        {"direction", std::string(core::plan::to_string(spec.direction))},
        {"producer_id", core::wire::to_string(spec.producer_id)},
        {"exchange_id", spec.exchange_id},
        {"length", plan.length},
        {"period_ms", spec.period.count()},
        {"signature",
         spec.signature.is_set() ? Json(core::wire::to_string(spec.signature)) : Json(nullptr)},
        // Consumed: when the tags turn stale (0: never); produced: where the datagrams go.
        {"timeout_ms", consumed ? Json(plan.timeout.count()) : Json(nullptr)},
        {"destination", consumed ? Json(nullptr) : Json(spec.destination)},
    };
    Json tags = Json::object();
    for (const auto& tag : plan.tags) tags[tag.spec.name] = tag_meta(tag);
    meta["tags"] = std::move(tags);
    // Names are text a broker accepts (validated); replace keeps a stray byte from throwing.
    return meta.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace eip2mqtt::app::northbound
