#include "adapters/mqtt/detail/connect_options.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace paho = ::mqtt;

void configure_connect_options(paho::connect_options& co, const ClientOptions& options,
                               const std::optional<BrokerEndpoint>& endpoint,
                               std::chrono::seconds connect_timeout) {
    const bool v5 = options.version == 5;
    co.set_mqtt_version(v5 ? MQTTVERSION_5 : MQTTVERSION_3_1_1);
    if (v5) {
        co.set_clean_start(options.clean_start);
        if (options.session_expiry.count() > 0) {
            co.set_properties(paho::properties{{paho::property::SESSION_EXPIRY_INTERVAL,
                                                static_cast<int>(options.session_expiry.count())}});
        }
    } else {
        co.set_clean_session(options.clean_start);
    }
    co.set_keep_alive_interval(options.keepalive);
    co.set_connect_timeout(connect_timeout);
    co.set_automatic_reconnect(false);  // we reconnect ourselves, initial connect included
    if (!options.username.empty() || !options.password.empty()) {
        co.set_user_name(options.username);
        co.set_password(options.password);
    }
    if (!options.availability_topic.empty()) {
        co.set_will(paho::will_options(options.availability_topic, std::string("offline"),
                                       options.availability_qos, true));
    }
    // TLS when the URL asks for it or a tls block is given. A tls block with a tcp:// URL is
    // passed to Paho as is, and Paho ignores it: the URL's scheme decides.
    if ((endpoint && endpoint->tls) || options.tls) {
        paho::ssl_options ssl;
        if (options.tls) {
            if (!options.tls->ca_file.empty()) {
                ssl.set_trust_store(options.tls->ca_file);
            }
            if (!options.tls->cert_file.empty()) {
                ssl.set_key_store(options.tls->cert_file);
            }
            if (!options.tls->key_file.empty()) {
                ssl.set_private_key(options.tls->key_file);
            }
            ssl.set_enable_server_cert_auth(options.tls->verify);
            ssl.set_verify(options.tls->verify);
        }
        // No set_error_handler: Paho C++ 1.2 keeps, through the copies connect() makes, a
        // pointer to a temporary ssl_options as the callback's context, and OpenSSL's first
        // error then crashes the process. on_connect explains a TLS failure instead.
        co.set_ssl(std::move(ssl));
    }
}

}  // namespace eip2mqtt::adapters::mqtt::detail
