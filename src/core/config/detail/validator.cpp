// The validator's run, and the checks of the gateway and mqtt sections.

#include "core/config/detail/validator.hpp"

#include <algorithm>
#include <array>
#include <tuple>

#include "core/config/detail/config_names.hpp"
#include "core/config/detail/connection_list_check.hpp"
#include "core/config/detail/redundancy_check.hpp"
#include "core/config/detail/sparkplug_check.hpp"
#include "core/config/detail/topic_layout_check.hpp"

namespace eip2mqtt::core::config::detail {

std::string too_long(std::string_view pattern, std::size_t bytes) {
    return "makes topic '" + std::string(pattern) + "' " + std::to_string(bytes) +
           " bytes long (MQTT allows " + std::to_string(plan::max_topic_bytes) + ")";
}

Diagnostics Validator::run() {
    check_gateway();
    check_mqtt();
    check_gateway_topics();
    check_exchanges();
    detail::check_topic_layout(config_, out_);
    detail::check_sparkplug(config_, out_);
    detail::check_redundancy(config_, out_);
    std::stable_sort(out_.begin(), out_.end(), [this](const Diagnostic& a, const Diagnostic& b) {
        return std::make_tuple(a.mark.file != config_.file, a.mark.file, a.mark.line,
                               a.mark.column) < std::make_tuple(b.mark.file != config_.file,
                                                                b.mark.file, b.mark.line,
                                                                b.mark.column);
    });
    return std::move(out_);
}

void Validator::check_gateway() {
    const auto& gateway = config_.gateway;
    id_ok_ = false;
    if (gateway.id.empty()) {
        error(gateway.marks.of("id"), "gateway id is empty");
    } else if (gateway.id.find_first_of("/+#") != std::string::npos) {
        error(gateway.marks.of("id"), "gateway id " + in_quotes(gateway.id) +
                                          " contains '/', '+' or '#' (it is a topic level)");
    } else if (const auto problem = plan::text_problem(gateway.id); !problem.empty()) {
        error(gateway.marks.of("id"), "gateway id " + in_quotes(gateway.id) + " " +
                                          std::string(problem) + " (it is a topic level)");
    } else {
        id_ok_ = true;
    }
    static constexpr std::array<std::string_view, 7> levels{"trace", "debug",    "info", "warn",
                                                            "error", "critical", "off"};
    if (std::find(levels.begin(), levels.end(), gateway.log_level) == levels.end()) {
        error(gateway.marks.of("log_level"),
              "log_level " + in_quotes(gateway.log_level) +
                  " is not one of trace, debug, info, warn, error, critical, off");
    }
}

void Validator::check_mqtt() {
    base_ok_ = check_connection(config_.mqtt);
    for (const auto& more : config_.more_mqtt) check_connection(more);
    detail::check_connection_list(config_, out_);
}

bool Validator::check_connection(const MqttSection& mqtt) {
    if (mqtt.version != 5 && mqtt.version != 3) {
        error(mqtt.marks.of("version"), "mqtt version must be 5 or 3.1.1");
    }
    if (mqtt.qos < 0 || mqtt.qos > 2) {
        error(mqtt.marks.of("qos"), "mqtt qos " + std::to_string(mqtt.qos) + " is not 0, 1 or 2");
    }
    const auto base_problem = topic_problem(mqtt.base_topic);
    bool base_ok = base_problem.empty();
    if (!base_ok) {
        error(mqtt.marks.of("base_topic"),
              "base_topic " + in_quotes(mqtt.base_topic) + " " + base_problem);
    } else if (mqtt.base_topic.front() == '$') {
        error(mqtt.marks.of("base_topic"), "base_topic " + in_quotes(mqtt.base_topic) +
                                               " starts with '$' (reserved by brokers)");
    }
    check_client_id(mqtt);
    check_connection_keys(mqtt);
    if (mqtt.metrics_interval.count() <= 0) {
        error(mqtt.marks.of("metrics_interval_s"), "metrics_interval_s must be at least 1");
    }
    return base_ok;
}

void Validator::check_client_id(const MqttSection& mqtt) {
    // Only a written one: the default, eip2mqtt-{gateway.id}, is as good as gateway.id.
    if (mqtt.marks.contains("client_id")) {
        if (const auto problem = plan::text_problem(mqtt.client_id); !problem.empty()) {
            error(mqtt.marks.of("client_id"),
                  "client_id " + in_quotes(mqtt.client_id) + " " + std::string(problem));
        } else if (mqtt.client_id.size() > max_string_bytes) {
            error(mqtt.marks.of("client_id"),
                  "client_id is " + std::to_string(mqtt.client_id.size()) +
                      " bytes long (MQTT allows " + std::to_string(max_string_bytes) + ")");
        }
    }
}

void Validator::check_connection_keys(const MqttSection& mqtt) {
    if (mqtt.urls.empty() ||
        std::any_of(mqtt.urls.begin(), mqtt.urls.end(), [](const auto& u) { return u.empty(); })) {
        error(mqtt.marks.of("url"), "mqtt url is empty");
    }
    if (mqtt.buffer_max_messages == 0) {
        error(mqtt.marks.of("buffer"), "buffer max_messages must be at least 1");
    }
    if (mqtt.batch_first && !mqtt.batch) {
        error(mqtt.marks.of("batch_first"),
              "batch_first puts _values first, and needs batch: true to have any");
    }
    if (mqtt.keepalive.count() <= 0) {
        error(mqtt.marks.of("keepalive_s"), "keepalive_s must be at least 1");
    }
}

void Validator::check_gateway_topics() {
    if (!base_ok_ || !id_ok_) return;
    const auto& base = config_.mqtt.base_topic;
    const auto& id = config_.gateway.id;
    constexpr std::string_view pattern = "{base_topic}/_gateway/{gateway.id}/metrics";
    const std::size_t fixed = base.size() + gateway_level.size() + metrics_suffix.size();
    if (fixed + 1 > plan::max_topic_bytes) {
        error(config_.mqtt.marks.of("base_topic"),
              "base_topic " + in_quotes(base) + " " + too_long(pattern, fixed + id.size()));
        base_ok_ = false;
    } else if (fixed + id.size() > plan::max_topic_bytes) {
        error(config_.gateway.marks.of("id"),
              "gateway id " + in_quotes(id) + " " + too_long(pattern, fixed + id.size()));
    }
}

}  // namespace eip2mqtt::core::config::detail
