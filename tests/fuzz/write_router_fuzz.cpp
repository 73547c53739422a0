// Fuzzes the MQTT write path as a client with write access drives it: any topic, payload,
// MQTT 5 response topic and correlation data, retained or not, through the WriteRouter of a
// gateway with a produced exchange of every tag type. Whatever comes in, the router must not
// crash, its answer must go to a topic a broker accepts and be JSON the gateway can dump, and
// what it accepts must be a value of the tag's type within the tag's limits.
//
// Input: one byte of flags (bit 0: retained), then topic, response topic and correlation data
// separated by 0xFF bytes (never part of UTF-8), then the payload (the rest, any bytes).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>
#include <variant>

#include "eip2mqtt/app/northbound/json_tree/write_router.hpp"
#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace {

using namespace eip2mqtt;
using core::plan::TagType;

core::plan::TagSpec tag(const char* name, std::uint16_t byte, std::uint8_t bit, TagType type,
                        bool writable = true) {
    core::plan::TagSpec spec;
    spec.name = name;
    spec.address = {byte, bit};
    spec.type = type;
    spec.writable = writable;
    return spec;
}

core::plan::ExchangePlan make_plan(const char* name, core::plan::Direction direction) {
    core::plan::ExchangeSpec spec;
    spec.name = name;
    spec.direction = direction;
    spec.producer_id = *core::wire::parse_producer_id("10.0.0.1");
    spec.exchange_id = direction == core::plan::Direction::produce ? 10 : 2;
    spec.length = 40;
    spec.topic = std::string("t1/") + name;
    spec.tags.push_back(tag("B", 0, 3, TagType::bit));
    spec.tags.push_back(tag("BY", 1, 0, TagType::byte));
    spec.tags.push_back(tag("I", 2, 0, TagType::int_));
    spec.tags.push_back(tag("W", 4, 0, TagType::word));
    auto limited = tag("D", 6, 0, TagType::dint);
    limited.mutable_extras().min = -100;
    limited.mutable_extras().max = 100.5;
    spec.tags.push_back(limited);
    spec.tags.push_back(tag("U", 10, 0, TagType::udint));
    spec.tags.push_back(tag("R", 14, 0, TagType::real));
    spec.tags.push_back(tag("L", 18, 0, TagType::lint));
    spec.tags.push_back(tag("LR", 26, 0, TagType::lreal));
    spec.tags.push_back(tag("RO", 34, 0, TagType::int_, false));
    return core::plan::make_exchange_plan(std::move(spec), "acme");
}

const core::plan::ExchangePlan produced = make_plan("sp", core::plan::Direction::produce);
const core::plan::ExchangePlan consumed = make_plan("in", core::plan::Direction::consume);

app::northbound::json_tree::WriteRouter make_router() {
    app::northbound::json_tree::WriteRouter router({"acme", false});
    router.add(produced);
    router.add(consumed);
    return router;
}

/// Takes the bytes up to the next 0xFF (or the end).
std::string take_field(std::string_view& rest) {
    const auto end = rest.find('\xFF');
    std::string field(rest.substr(0, end));
    rest.remove_prefix(end == std::string_view::npos ? rest.size() : end + 1);
    return field;
}

/// The accepted value fits its tag: the right alternative, in range, within min/max.
bool fits(const core::plan::TagSpec& spec, const core::plan::Value& value) {
    const double v = core::plan::to_double(value);
    if (spec.min() && v < *spec.min()) return false;
    if (spec.max() && v > *spec.max()) return false;
    switch (spec.type) {
        case TagType::bit:
            return std::holds_alternative<bool>(value);
        case TagType::real:
            return std::holds_alternative<float>(value) && std::isfinite(v);
        case TagType::lreal:
            return std::holds_alternative<double>(value) && std::isfinite(v);
        case TagType::int_:
        case TagType::dint:
        case TagType::lint:
            return std::holds_alternative<std::int64_t>(value) &&
                   v >= core::plan::type_min(spec.type) && v <= core::plan::type_max(spec.type);
        default:
            return std::holds_alternative<std::uint64_t>(value) &&
                   v <= core::plan::type_max(spec.type);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const app::northbound::json_tree::WriteRouter router = make_router();
    if (size == 0) return 0;
    std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
    adapters::mqtt::Incoming message;
    message.retained = (data[0] & 1) != 0;
    message.topic = take_field(rest);
    message.response_topic = take_field(rest);
    message.correlation_data = take_field(rest);
    message.payload = std::string(rest);

    const auto decision = router.route(message);
    if (!decision) return 0;
    // The answer must be publishable (a broker closes the connection on a bad topic), or be
    // left unpublished (an empty topic) when the write is refused anyway.
    const auto* rejection = std::get_if<core::write::WriteRejection>(&decision->outcome);
    const bool unanswered = rejection != nullptr && decision->reply.topic.empty();
    if (!unanswered && !core::plan::topic_name_problem(decision->reply.topic).empty()) {
        __builtin_trap();
    }
    if (rejection != nullptr) {
        // As Gateway::reject_write builds it: must not throw.
        const nlohmann::json result = {{"ok", false}, {"error", rejection->message}};
        (void)result.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
        return 0;
    }
    const auto& routed = std::get<app::ExchangeWrite>(decision->outcome);
    if (message.retained || routed.writes.empty() || routed.producer != &produced) __builtin_trap();
    for (const auto& write : routed.writes) {
        if (write.tag_index >= produced.tags.size()) __builtin_trap();
        const auto& spec = produced.tags[write.tag_index].spec;
        if (!spec.writable || !fits(spec, write.value)) __builtin_trap();
    }
    return 0;
}
