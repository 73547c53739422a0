#include "adapters/mqtt/detail/publish_properties.hpp"

#include <string_view>

namespace eip2mqtt::adapters::mqtt::detail {

::mqtt::message_ptr availability_message(const ClientOptions& options, const std::string& text) {
    auto message =
        ::mqtt::make_message(options.availability_topic, text, options.availability_qos, true);
    if (options.describe_payloads && options.version == 5) {
        message->set_properties({{::mqtt::property::CONTENT_TYPE, "text/plain"},
                                 {::mqtt::property::PAYLOAD_FORMAT_INDICATOR, 1}});
    }
    return message;
}

void PublishProperties::on_connected(std::uint16_t alias_maximum) {
    alias_maximum_.store(alias_maximum, std::memory_order_relaxed);
    connection_.fetch_add(1, std::memory_order_release);
}

std::uint16_t PublishProperties::alias_of(const std::string& topic, bool& known) {
    const auto connection = connection_.load(std::memory_order_acquire);
    if (connection != aliases_of_) {
        aliases_.clear();
        aliases_of_ = connection;
    }
    if (const auto it = aliases_.find(topic); it != aliases_.end()) {
        known = true;
        return it->second;
    }
    known = false;
    const auto maximum = alias_maximum_.load(std::memory_order_relaxed);
    if (aliases_.size() >= maximum) return 0;
    const auto alias = static_cast<std::uint16_t>(aliases_.size() + 1);
    aliases_.emplace(topic, alias);
    return alias;
}

::mqtt::message_ptr PublishProperties::to_paho(const Message& message) {
    const bool expires = message.live && options_.message_expiry.count() > 0;
    // Most of Sparkplug's and the pair's publications carry no property: no list built.
    const bool described = !message.correlation_data.empty() || message.historical ||
                           !message.user_properties.empty() || options_.describe_payloads ||
                           expires || options_.topic_aliases;
    if (options_.version != 5 || !described) {
        return ::mqtt::make_message(message.topic, message.payload, message.qos, message.retain);
    }
    ::mqtt::properties properties;
    if (!message.correlation_data.empty()) {
        properties.add({::mqtt::property::CORRELATION_DATA, message.correlation_data});
    }
    if (message.historical) {
        properties.add({::mqtt::property::USER_PROPERTY, "historical", "true"});
    }
    const std::string_view pairs = message.user_properties;
    for (std::size_t at = 0; at < pairs.size();) {
        const auto name_end = pairs.find('\0', at);
        const auto value_end = pairs.find('\0', name_end + 1);
        if (name_end == std::string_view::npos || value_end == std::string_view::npos) break;
        properties.add({::mqtt::property::USER_PROPERTY,
                        std::string(pairs.substr(at, name_end - at)),
                        std::string(pairs.substr(name_end + 1, value_end - name_end - 1))});
        at = value_end + 1;
    }
    if (options_.describe_payloads) {
        properties.add(
            {::mqtt::property::CONTENT_TYPE, message.text ? "text/plain" : "application/json"});
        properties.add({::mqtt::property::PAYLOAD_FORMAT_INDICATOR, 1});
    }
    if (expires) {
        properties.add({::mqtt::property::MESSAGE_EXPIRY_INTERVAL,
                        static_cast<int>(options_.message_expiry.count())});
    }
    // Only live values repeat often enough to earn one of the broker's few aliases (Mosquitto
    // grants 10): the state, `_status` and `_meta` sent first would otherwise take them all.
    bool known = false;
    const auto alias = options_.topic_aliases && message.live ? alias_of(message.topic, known) : 0;
    if (alias != 0) properties.add({::mqtt::property::TOPIC_ALIAS, alias});
    if (known) aliased_.fetch_add(1, std::memory_order_relaxed);
    auto out = ::mqtt::make_message(known ? std::string() : message.topic, message.payload,
                                    message.qos, message.retain);
    if (!properties.empty()) out->set_properties(std::move(properties));
    return out;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
