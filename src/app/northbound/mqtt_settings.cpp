#include "eip2mqtt/app/northbound/mqtt_settings.hpp"

#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace eip2mqtt::app {
namespace {

std::string first_line(const std::string& path, const std::string& what) {
    std::ifstream file(path);
    if (!file) throw std::runtime_error("cannot read " + what);
    std::string line;
    std::getline(file, line);
    return line;
}

/// Where systemd put the unit's credentials (LoadCredential=); empty outside such a unit.
std::string credentials_directory() {
    const char* directory = std::getenv("CREDENTIALS_DIRECTORY");
    return directory != nullptr ? directory : "";
}

std::string read_password_file(const std::string& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) == 0 && (info.st_mode & S_IROTH) != 0) {
        spdlog::warn("password file {} is readable by others; chmod o-r it", path);
    }
    std::string what = "mqtt.password_file " + path;
    if (path.find('/') == std::string::npos) {
        what +=
            " (a name without a slash is a systemd credential only where $CREDENTIALS_DIRECTORY "
            "is set, in a unit with LoadCredential=" +
            path + ")";
    }
    return first_line(path, what);
}

}  // namespace

std::string read_mqtt_password(const core::config::MqttSection& mqtt) {
    const auto credentials = credentials_directory();
    const auto& file = mqtt.password_file;
    if (!file.empty() && !credentials.empty() && file.find('/') == std::string::npos) {
        const auto path = credentials + "/" + file;
        return first_line(path, "mqtt.password_file: the systemd credential " + file + " (" + path +
                                    "); the unit needs LoadCredential=" + file);
    }
    if (!file.empty()) return read_password_file(file);
    if (!credentials.empty()) {
        const auto path = credentials + "/" + std::string(default_password_credential);
        if (::access(path.c_str(), F_OK) == 0) {
            return first_line(path, "the systemd credential " +
                                        std::string(default_password_credential) + " (" + path +
                                        ")");
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

adapters::mqtt::ClientOptions mqtt_client_options(const core::config::Config& config,
                                                  const std::string& availability_topic) {
    const auto& mqtt = config.mqtt;
    adapters::mqtt::ClientOptions options;
    options.urls = mqtt.urls;
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
    // MQTT 5 metadata (docs/mqtt-api.md): the gateway's JSON and text say what they are.
    options.describe_payloads = true;
    options.message_expiry = mqtt.message_expiry;
    // Paho re-sends a kept session's publications as they were: aliases need a clean start.
    options.topic_aliases = mqtt.topic_aliases && options.clean_start;
    return options;
}

adapters::mqtt::ClientOptions sparkplug_client_options(
    const core::config::Config& config, std::function<adapters::mqtt::Message()> will) {
    auto options = mqtt_client_options(config, {});
    options.client_id += "-sparkplug";
    options.log_name = "MQTT (Sparkplug)";
    // Protobuf, described by Sparkplug itself; its births already alias its metrics.
    options.describe_payloads = false;
    options.message_expiry = std::chrono::seconds(0);
    options.topic_aliases = false;
    options.session_expiry = std::chrono::seconds(0);
    options.clean_start = true;
    options.will = std::move(will);
    // Sparkplug B 3.0 over MQTT 5: a DISCONNECT says the NDEATH too.
    options.disconnect_with_will = true;
    options.session_bound = true;
    // Hears its own publications back (ClientOptions::hear_own).
    options.hear_own = true;
    return options;
}

}  // namespace eip2mqtt::app
