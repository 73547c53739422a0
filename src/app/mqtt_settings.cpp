#include "eip2mqtt/app/mqtt_settings.hpp"

#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace eip2mqtt::app {

std::string read_mqtt_password(const core::config::MqttSection& mqtt) {
    if (!mqtt.password_file.empty()) {
        struct stat info {};
        if (::stat(mqtt.password_file.c_str(), &info) == 0 && (info.st_mode & S_IROTH) != 0) {
            spdlog::warn("password file {} is readable by others; chmod o-r it",
                         mqtt.password_file);
        }
        std::ifstream file(mqtt.password_file);
        if (!file) {
            throw std::runtime_error("cannot read mqtt.password_file " + mqtt.password_file);
        }
        std::string password;
        std::getline(file, password);
        return password;
    }
    if (const char* env = std::getenv("EIP2MQTT_MQTT_PASSWORD")) return env;
    return {};
}

adapters::mqtt::ClientOptions mqtt_client_options(const core::config::Config& config,
                                                  const std::string& availability_topic) {
    const auto& mqtt = config.mqtt;
    adapters::mqtt::ClientOptions options;
    options.url = mqtt.url;
    options.client_id = mqtt.client_id.empty() ? "eip2mqtt-" + config.gateway.id : mqtt.client_id;
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
    options.availability_topic = availability_topic;
    options.buffer_max_messages = mqtt.buffer_max_messages;
    options.batch_first = mqtt.batch_first;
    return options;
}

adapters::mqtt::ClientOptions sparkplug_client_options(
    const core::config::Config& config, std::function<adapters::mqtt::Message()> will) {
    auto options = mqtt_client_options(config, {});
    options.client_id += "-sparkplug";
    options.log_name = "MQTT (Sparkplug)";
    options.session_expiry = std::chrono::seconds(0);
    options.clean_start = true;
    options.will = std::move(will);
    options.session_bound = true;
    return options;
}

}  // namespace eip2mqtt::app
