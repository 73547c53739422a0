#pragma once
/// The MQTT client's options from the configuration: the client id's default, the session, TLS,
/// and the password, which never comes from the YAML (docs/configuration.md). Apart from
/// reading the password file, a pure function of the configuration.

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app {

/// The systemd credential the packaged unit loads (LoadCredential=mqtt-password), read when
/// mqtt.password_file is not set.
inline constexpr std::string_view default_password_credential = "mqtt-password";

/// The MQTT password, from the first of these that gives one:
/// - mqtt.password_file, a name without a slash while $CREDENTIALS_DIRECTORY is set (a unit
///   with LoadCredential=): the first line of the credential of that name;
/// - mqtt.password_file, otherwise a path: the first line of that file (warned about when
///   others may read it);
/// - mqtt.password_file not set: the first line of the credential `mqtt-password`, if the unit
///   passed one;
/// - the environment variable EIP2MQTT_MQTT_PASSWORD;
/// else empty. Throws std::runtime_error naming what could not be read when the file, or the
/// credential password_file names, cannot be read.
std::string read_mqtt_password(const core::config::MqttSection& mqtt);

/// `mqtt.url`'s brokers for a log line or `check`: "tcp://a:1883", or
/// "tcp://a:1883, then tcp://b:1883" when there are several.
std::string broker_list(const std::vector<std::string>& urls);

/// The brokers of the start's log line: the first connection's, and how many connections more.
std::string brokers_line(const core::config::Config& config);

/// What `check` says of the MQTT connections: the brokers tried in turn of a lone connection
/// with several (else nothing), or a line per connection of a list. Each line ends in '\n'.
std::string connections_summary(const core::config::Config& config);

/// The QoS a connection subscribes at: 0 for a clean session over MQTT 3.1.1 (`version` 3),
/// else 1 (mqtt_settings.cpp says why).
int subscription_qos(int version, bool clean_start);

/// The client id of connection `connection` (core::config::mqtt_connection) when it sets none:
/// eip2mqtt-{gateway.id}, with -{name} after the first connection.
std::string default_client_id(const core::config::Config& config, std::size_t connection);

/// Options of the gateway's MQTT client on connection `connection` (core::config::
/// mqtt_connection; 0, the first, by default); `availability_topic` carries its will.
adapters::mqtt::ClientOptions mqtt_client_options(const core::config::Config& config,
                                                  const std::string& availability_topic,
                                                  std::size_t connection = 0);

/// Options of the Sparkplug edge node's own connection: the brokers of the connection
/// `sparkplug.connection` names (core::config::sparkplug_connection), the same credentials and TLS,
/// client id `{client id}-sparkplug`, a clean session every time (Sparkplug B 3.0), session-bound,
/// `will` making each CONNECT's NDEATH.
adapters::mqtt::ClientOptions sparkplug_client_options(
    const core::config::Config& config, std::function<adapters::mqtt::Message()> will);

}  // namespace eip2mqtt::app
