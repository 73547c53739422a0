#include "eip2mqtt/app/redundancy/pair_connection.hpp"

#include <utility>

#include "eip2mqtt/app/northbound/mqtt_settings.hpp"
#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app::redundancy {
namespace {

/// An adapters::mqtt::Client as the pair's connection: every call handed on as it is.
class MqttPairConnection final : public PairConnection {
public:
    MqttPairConnection(boost::asio::any_io_executor loop, adapters::mqtt::ClientOptions options)
        : client_(std::move(loop), std::move(options)) {}

    void publish(adapters::mqtt::Message&& message) override {
        client_.publish(std::move(message));
    }
    void set_subscriptions(std::vector<std::string> filters) override {
        client_.set_subscriptions(std::move(filters));
    }
    void set_on_connected(Connected handler) override {
        client_.set_on_connected(std::move(handler));
    }
    void set_on_message(Heard handler) override { client_.set_on_message(std::move(handler)); }
    void set_on_acknowledged(Acknowledged handler) override {
        client_.set_on_acknowledged(std::move(handler));
    }
    void start() override { client_.start(); }
    void stop(std::chrono::milliseconds flush_timeout) override { client_.stop(flush_timeout); }
    bool connected() const override { return client_.connected(); }

private:
    adapters::mqtt::Client client_;
};

}  // namespace

adapters::mqtt::ClientOptions pair_client_options(const core::config::Config& config,
                                                  adapters::mqtt::Message will) {
    auto options = mqtt_client_options(config, {});
    options.client_id += "-pair";
    options.log_name = "MQTT (pair)";
    options.session_expiry = std::chrono::seconds(0);
    options.clean_start = true;
    options.subscription_qos = subscription_qos(config.mqtt.version, options.clean_start);
    options.will = [will = std::move(will)] { return will; };
    options.session_bound = true;
    options.hear_own = true;  // a claim heard back confirms it (core/redundancy/lease.hpp)
    // An image heard back live, not fetched from the store, gives a late answer (PairImages).
    options.retain_as_published = false;
    // A lease's records are few and short-lived on the wire: named in full.
    options.topic_aliases = false;
    return options;
}

PairConnector mqtt_pair_connector(boost::asio::any_io_executor loop) {
    return
        [loop = std::move(loop)](const core::config::Config& config,
                                 adapters::mqtt::Message will) -> std::unique_ptr<PairConnection> {
            return std::make_unique<MqttPairConnection>(
                loop, pair_client_options(config, std::move(will)));
        };
}

}  // namespace eip2mqtt::app::redundancy
