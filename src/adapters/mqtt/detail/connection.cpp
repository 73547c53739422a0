// The Connection's way up: Paho's callbacks, connect, the CONNACK, subscriptions, `online`.

#include "adapters/mqtt/detail/connection.hpp"

#include <spdlog/spdlog.h>

#include <utility>

#include "adapters/mqtt/detail/connect_options.hpp"
#include "adapters/mqtt/detail/paho_tokens.hpp"
#include "adapters/mqtt/detail/publication_check.hpp"
#include "adapters/mqtt/detail/publish_properties.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace paho = ::mqtt;

namespace {

constexpr auto kConnectTimeout = std::chrono::seconds(10);

Incoming to_incoming(const paho::const_message_ptr& msg) {
    Incoming in;
    in.topic = msg->get_topic();
    in.payload = msg->get_payload_str();
    in.retained = msg->is_retained();
    const paho::properties& props = msg->get_properties();
    if (props.contains(paho::property::RESPONSE_TOPIC)) {
        in.response_topic = paho::get<std::string>(props, paho::property::RESPONSE_TOPIC);
    }
    if (props.contains(paho::property::CORRELATION_DATA)) {
        in.correlation_data = paho::get<std::string>(props, paho::property::CORRELATION_DATA);
    }
    if (props.contains(paho::property::MESSAGE_EXPIRY_INTERVAL)) {
        in.message_expiry_s =
            paho::get<std::uint32_t>(props, paho::property::MESSAGE_EXPIRY_INTERVAL);
    }
    return in;
}

}  // namespace

void Connection::ConnectListener::on_success(const paho::token&) {
    connection_.loop_.post([&c = connection_] { c.on_connect(true, {}); });
}

void Connection::ConnectListener::on_failure(const paho::token& tok) {
    connection_.loop_.post(
        [&c = connection_, reason = describe_failure(tok), rc = tok.get_return_code()]() mutable {
            c.on_connect(false, std::move(reason), rc);
        });
}

Connection::Connection(const ClientOptions& options, paho::async_client& paho, const LoopPost& loop,
                       Sender& sender, NagleSwitch& nagle)
    : options_(options),
      paho_(paho),
      loop_(loop),
      sender_(sender),
      nagle_(nagle),
      brokers_(options.urls),
      reconnect_(loop, options),
      diagnosis_(options),
      subscriptions_(options, paho, loop, brokers_) {
    // The configuration gives every broker of a list the same scheme: the first one's TLS
    // settings are everyone's.
    configure_connect_options(connect_options_, options_, brokers_.first_endpoint(),
                              kConnectTimeout);
    if (options_.tls && brokers_.endpoint() && !brokers_.endpoint()->tls) {
        spdlog::warn("{} url {} is not ssl:// or wss://: mqtt.tls is ignored", options_.log_name,
                     brokers_.url());
    }
    install_callbacks();
}

void Connection::install_callbacks() {
    // Paho's threads: copy, count, post; nothing else.
    paho_.set_connection_lost_handler([this](const std::string& cause) {
        sender_.set_link_up(false);
        loop_.post([this, cause] { on_connection_lost(cause, cause.empty()); });
    });
    paho_.set_disconnected_handler([this](const paho::properties&, paho::ReasonCode reason) {
        sender_.set_link_up(false);
        loop_.post([this, reason] {
            on_connection_lost(describe_disconnect(static_cast<int>(reason),
                                                   paho::exception::reason_code_str(reason),
                                                   options_.client_id));
        });
    });
    paho_.set_message_callback([this](paho::const_message_ptr msg) { on_message_arrived(msg); });
}

void Connection::on_message_arrived(const paho::const_message_ptr& msg) {
    ConnectionCounters::bump(counters_.received);
    loop_.post([this, in = to_incoming(msg)]() mutable {
        if (on_message_ && state_ != State::stopped) {
            on_message_(std::move(in));
        }
    });
}

void Connection::start() {
    if (state_ == State::idle) {
        do_connect();
    } else if (state_ == State::ending) {
        start_pending_ = true;
    }
}

void Connection::do_connect() {
    if (state_ == State::stopped) {
        return;
    }
    state_ = State::connecting;
    try {
        if (options_.will) {
            Message will = options_.will();
            connect_options_.set_will(
                paho::will_options(will.topic, will.payload, will.qos, will.retain));
            last_will_.set(std::move(will));
        }
        // One Paho client for every broker of the list: a connect's server list replaces the
        // URI the client was made with (Paho C frees and copies it on each connect). A client
        // per broker would need the Sender's in-flight ledger, the will and the callbacks moved
        // from one to the next; with one, they stay, and so does everything after a connect.
        // A list of one URL each time: given them all, Paho would walk them from the first on
        // every connect and fail only after the last, where each attempt here goes to the next
        // broker, with the backoff between, and is logged with its URL.
        connect_options_.set_servers(paho::string_collection::create({brokers_.url()}));
        connect_token_ = paho_.connect(connect_options_, nullptr, connect_listener_);
    } catch (const paho::exception& e) {
        on_connect(false, e.what());
    }
}

void Connection::on_connect(bool ok, std::string reason, int return_code) {
    if (state_ != State::connecting) {
        return;  // stopped meanwhile
    }
    if (ok && !paho_.is_connected()) {
        ok = false;  // lost again before this ran
        reason = "connection lost right after connect";
    }
    if (!ok) {
        on_connect_failed(std::move(reason), return_code);
        return;
    }
    on_connected();
}

void Connection::on_connected() {
    state_ = State::connected;
    diagnosis_.on_connected();
    sender_.set_link_up(true);
    counters_.connected = true;
    ConnectionCounters::bump(counters_.connects);
    reconnect_.reset();
    apply_broker_limits();
    spdlog::info("{} connected to {}", options_.log_name, brokers_.url());

    if (const auto& endpoint = brokers_.endpoint()) {
        nagle_.attach(sockets_connected_to(endpoint->host, endpoint->port));
    }
    // Subscribe before announcing `online`: the broker handles one connection's packets in
    // order, so whoever sees `online` can already write to us.
    subscriptions_.renew();
    announce_online();
    if (on_connected_) {
        on_connected_();
    }
    sender_.set_sending(true);
}

void Connection::apply_broker_limits() {
    // MQTT 5 §3.2.2.3.3: the broker's Receive Maximum, 65535 when absent (Mosquitto sends 20).
    // Paho C sends no more QoS >= 1 publications than that and queues the rest until its next
    // one-second cycle rather than on PUBACK: the sender must not hand it more of them
    // (detail/send_room.hpp). (The token the listener sees lacks the CONNACK properties in
    // Paho C++ 1.2; the one connect() returned has them.)
    std::size_t receive_maximum = 65535;
    std::optional<std::size_t> max_packet_size;  // kept from the last connection when unread
    std::uint16_t topic_alias_maximum = 0;       // MQTT 5 §3.2.2.3.8: none when absent
    try {
        // The listener posted on_connect just before Paho marks the token complete and
        // stores the response: wait for that (microseconds; bounded).
        if (connect_token_ && connect_token_->wait_for(std::chrono::seconds(1))) {
            const paho::connect_response response = connect_token_->get_connect_response();
            const paho::properties& props = response.get_properties();
            if (props.contains(paho::property::RECEIVE_MAXIMUM)) {
                receive_maximum = paho::get<std::uint16_t>(props, paho::property::RECEIVE_MAXIMUM);
            }
            if (props.contains(paho::property::TOPIC_ALIAS_MAXIMUM)) {
                topic_alias_maximum =
                    paho::get<std::uint16_t>(props, paho::property::TOPIC_ALIAS_MAXIMUM);
            }
            max_packet_size =
                props.contains(paho::property::MAXIMUM_PACKET_SIZE)
                    ? paho::get<std::uint32_t>(props, paho::property::MAXIMUM_PACKET_SIZE)
                    : max_mqtt_packet_size;
        }
    } catch (const std::exception&) {
        // No CONNACK properties (MQTT 3.1.1): no limit beyond ours.
    }
    sender_.on_connected(receive_maximum, max_packet_size, topic_alias_maximum);
}

void Connection::announce_online() {
    try {
        if (!options_.availability_topic.empty()) {
            const int qos = options_.availability_qos;
            sender_.publish_own(availability_message(options_, "online"),
                                qos > 0 ? sender_.reserve_own_slot() : 0);
        }
    } catch (const paho::exception& e) {
        spdlog::warn("{} cannot publish availability: {}", options_.log_name, e.what());
    }
}

void Connection::set_subscriptions(std::vector<std::string> filters) {
    subscriptions_.set(std::move(filters), state_ == State::connected);
}

}  // namespace eip2mqtt::adapters::mqtt::detail
