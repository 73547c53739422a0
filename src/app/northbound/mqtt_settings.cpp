#include "eip2mqtt/app/northbound/mqtt_settings.hpp"

#include <unistd.h>

#include <cstdlib>

#include "app/detail/secret_file.hpp"

namespace eip2mqtt::app {

std::string read_mqtt_password(const core::config::MqttSection& mqtt) {
    if (!mqtt.password_file.empty()) {
        return detail::read_secret_file(mqtt.password_file, "mqtt.password_file");
    }
    const auto credentials = detail::credentials_directory();
    if (!credentials.empty()) {
        const auto path = credentials + "/" + std::string(default_password_credential);
        if (::access(path.c_str(), F_OK) == 0) {
            return detail::first_line(path, "the systemd credential " +
                                                std::string(default_password_credential) + " (" +
                                                path + ")");
        }
    }
    if (const char* env = std::getenv("EIP2MQTT_MQTT_PASSWORD")) return env;
    return {};
}

std::string broker_list(const std::vector<std::string>& urls) {
    std::string out;
    for (const auto& url : urls) {
        out += (out.empty() ? "" : ", then ") + url;
    }
    return out;
}

std::string brokers_line(const core::config::Config& config) {
    auto line = broker_list(config.mqtt.urls);
    if (!config.more_mqtt.empty()) {
        line += " and " + std::to_string(config.more_mqtt.size()) + " more connection(s)";
    }
    return line;
}

std::string connections_summary(const core::config::Config& config) {
    const auto connections = core::config::mqtt_connections(config);
    if (connections.size() == 1) {
        const auto& urls = config.mqtt.urls;
        return urls.size() > 1 ? "brokers, tried in turn: " + broker_list(urls) + "\n" : "";
    }
    std::string out;
    for (std::size_t i = 0; i < connections.size(); ++i) {
        const auto& mqtt = *connections[i];
        out += "mqtt connection " + core::config::connection_name(mqtt) + ": " +
               broker_list(mqtt.urls) + ", base topic " + mqtt.base_topic +
               (core::config::takes_writes(mqtt, i) ? ", takes writes" : "") +
               (mqtt.store_and_forward.enabled ? ", store and forward" : "") + "\n";
    }
    return out;
}

// A clean session gains nothing from QoS 1 on the way in: what a lost connection held is
// dropped with the session either way. RabbitMQ before 3.13 (MQTT 3.1.1 only) keeps a QoS 1
// subscription in a durable queue on the node the client used, clean session or not; once that
// node is down, every other node of its cluster closes a connection of the same client id as it
// subscribes again (docs/brokers.md). So over 3.1.1 a clean session subscribes at QoS 0.
int subscription_qos(int version, bool clean_start) { return version == 3 && clean_start ? 0 : 1; }

std::string default_client_id(const core::config::Config& config, std::size_t connection) {
    auto id = "eip2mqtt-" + config.gateway.id;
    // Two connections of one gateway may reach one broker: each needs an id of its own.
    if (connection > 0)
        id +=
            "-" + core::config::connection_name(core::config::mqtt_connection(config, connection));
    return id;
}

adapters::mqtt::ClientOptions mqtt_client_options(const core::config::Config& config,
                                                  const std::string& availability_topic,
                                                  std::size_t connection) {
    const auto& mqtt = core::config::mqtt_connection(config, connection);
    adapters::mqtt::ClientOptions options;
    options.urls = mqtt.urls;
    options.client_id =
        mqtt.client_id.empty() ? default_client_id(config, connection) : mqtt.client_id;
    if (!config.more_mqtt.empty())
        options.log_name = "MQTT [" + core::config::connection_name(mqtt) + "]";
    options.version = mqtt.version;
    options.username = mqtt.username;
    options.password = read_mqtt_password(mqtt);
    if (mqtt.tls) {
        options.tls = adapters::mqtt::TlsOptions{mqtt.tls->ca_file, mqtt.tls->cert_file,
                                                 mqtt.tls->key_file, mqtt.tls->verify};
    }
    options.keepalive = mqtt.keepalive;
    options.session_expiry = mqtt.session_expiry;
    options.clean_start = mqtt.session_expiry.count() == 0;
    options.subscription_qos = subscription_qos(mqtt.version, options.clean_start);
    options.availability_topic = availability_topic;
    options.buffer_max_messages = mqtt.buffer_max_messages;
    options.batch_first = mqtt.batch_first;
    // MQTT 5 metadata (docs/mqtt-api.md): the gateway's JSON and text say what they are,
    // unless the plant gives that up for throughput (docs/performance.md).
    options.describe_payloads = mqtt.describe_payloads;
    options.message_expiry = mqtt.message_expiry;
    // Paho re-sends a kept session's publications as they were: aliases need a clean start.
    options.topic_aliases = mqtt.topic_aliases && options.clean_start;
    return options;
}

adapters::mqtt::ClientOptions sparkplug_client_options(
    const core::config::Config& config, std::function<adapters::mqtt::Message()> will) {
    const auto connection = core::config::sparkplug_connection(config);
    auto options = mqtt_client_options(config, {}, connection);
    // The connection's id, given or not: a given one is its JSON tree's already.
    options.client_id += "-sparkplug";
    options.log_name = "MQTT (Sparkplug)";
    // Protobuf, described by Sparkplug itself; its births already alias its metrics.
    options.describe_payloads = false;
    options.message_expiry = std::chrono::seconds(0);
    options.topic_aliases = false;
    options.session_expiry = std::chrono::seconds(0);
    options.clean_start = true;
    // Its commands and its host's STATE keep QoS 1 over 3.1.1 too: on a RabbitMQ cluster before
    // 3.13 it waits for its node to return (docs/brokers.md).
    options.subscription_qos = 1;
    options.will = std::move(will);
    // Sparkplug B 3.0 over MQTT 5: a DISCONNECT says the NDEATH too.
    options.disconnect_with_will = true;
    options.session_bound = true;
    // Hears its own publications back (ClientOptions::hear_own).
    options.hear_own = true;
    return options;
}

}  // namespace eip2mqtt::app
