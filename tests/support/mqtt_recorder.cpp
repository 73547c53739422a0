#include "tests/support/mqtt_recorder.hpp"

#include <mqtt/async_client.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <utility>

namespace eip2mqtt::test {
namespace {

constexpr auto kOperationTimeout = std::chrono::seconds(10);
/// Long enough for any test; the session is ended explicitly on destruction.
constexpr int kSessionExpiry_s = 3600;

std::string unique_client_id() {
    static std::atomic<unsigned> counter{0};
    const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
    return "recorder-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + "-" +
           std::to_string(now);
}

void wait_ok(const ::mqtt::token_ptr& tok, const char* what) {
    if (!tok->wait_for(kOperationTimeout)) {
        throw std::runtime_error(std::string("MqttRecorder: ") + what + " timed out");
    }
    tok->get_return_code();
}

/// Connect options for `login`'s protocol: a session that outlives a connection by an hour over
/// MQTT 5, a persistent session over 3.1.1 (which has no expiry).
::mqtt::connect_options connect_options_for(const MqttLogin& login, bool clean) {
    ::mqtt::connect_options options;
    if (!login.username.empty()) {
        options.set_user_name(login.username);
        options.set_password(login.password);
    }
    options.set_mqtt_version(login.version);
    if (login.version >= MQTTVERSION_5) {
        options.set_clean_start(clean);
        options.set_properties({{::mqtt::property::SESSION_EXPIRY_INTERVAL, kSessionExpiry_s}});
    } else {
        options.set_clean_session(clean);
    }
    return options;
}

}  // namespace

struct MqttRecorder::Impl {
    Impl(const std::string& url, const std::string& id, std::vector<std::string> filters,
         int version)
        : client(url, id, ::mqtt::create_options(version)),
          filters(std::move(filters)),
          version(version) {}

    ::mqtt::async_client client;
    std::vector<std::string> filters;
    int version;
    std::atomic<bool> subscribed_once{false};

    mutable std::mutex mutex;
    std::condition_variable cv;
    std::vector<Received> messages;

    void record(const ::mqtt::const_message_ptr& msg) {
        Received r;
        r.topic = msg->get_topic();
        r.payload = msg->get_payload_str();
        r.retained = msg->is_retained();
        r.duplicate = msg->is_duplicate();
        r.at = std::chrono::steady_clock::now();
        const auto& props = msg->get_properties();
        if (props.contains(::mqtt::property::CORRELATION_DATA)) {
            r.correlation_data =
                ::mqtt::get<std::string>(props, ::mqtt::property::CORRELATION_DATA);
        }
        if (props.contains(::mqtt::property::CONTENT_TYPE)) {
            r.content_type = ::mqtt::get<std::string>(props, ::mqtt::property::CONTENT_TYPE);
        }
        if (props.contains(::mqtt::property::PAYLOAD_FORMAT_INDICATOR)) {
            r.payload_format =
                ::mqtt::get<std::uint8_t>(props, ::mqtt::property::PAYLOAD_FORMAT_INDICATOR);
        }
        if (props.contains(::mqtt::property::MESSAGE_EXPIRY_INTERVAL)) {
            r.message_expiry_s =
                ::mqtt::get<std::uint32_t>(props, ::mqtt::property::MESSAGE_EXPIRY_INTERVAL);
        }
        for (std::size_t i = 0; i < props.count(::mqtt::property::USER_PROPERTY); ++i) {
            auto [name, value] =
                ::mqtt::get<::mqtt::string_pair>(props, ::mqtt::property::USER_PROPERTY, i);
            r.user_properties.emplace_back(std::move(name), std::move(value));
        }
        {
            std::lock_guard lock(mutex);
            messages.push_back(std::move(r));
        }
        cv.notify_all();
    }

    /// retain_as_published so tests can assert the retain flag of live publications;
    /// SEND_RETAINED_ON_NEW so a renewed subscription does not replay retained messages.
    ::mqtt::token_ptr subscribe(::mqtt::subscribe_options::RetainHandling handling) {
        const ::mqtt::subscribe_options opt(false, true, handling);
        // One SUBSCRIBE a filter: Paho C reads a one-topic SUBSCRIBE's options from a field
        // Paho C++ 1.2's collection overload leaves unset, and its many-topic one crashed in
        // MQTTAsync_subscribeMany. They complete in order: the last token says all are done.
        ::mqtt::token_ptr last;
        for (const auto& filter : filters) {
            last = version >= MQTTVERSION_5 ? client.subscribe(filter, 1, opt)
                                            : client.subscribe(filter, 1);
        }
        return last;
    }
};

MqttRecorder::MqttRecorder(const std::string& url, const std::vector<std::string>& filters,
                           const std::string& client_id, const MqttLogin& login)
    : impl_(std::make_unique<Impl>(url, client_id.empty() ? unique_client_id() : client_id, filters,
                                   login.version)) {
    auto& cli = impl_->client;
    Impl* impl = impl_.get();
    cli.set_message_callback([impl](::mqtt::const_message_ptr msg) { impl->record(msg); });
    // The broker may have lost the session (restart without persistence): subscribe again.
    cli.set_connected_handler([impl](const std::string&) {
        if (impl->subscribed_once && !impl->filters.empty()) {
            impl->subscribe(::mqtt::subscribe_options::SEND_RETAINED_ON_NEW);
        }
    });

    // A clean start, so nothing of an earlier session with this id leaks in, but then resume
    // that session without clean start and with automatic reconnect, so that reconnects (after
    // a broker restart) keep the subscriptions and the QoS 1 messages queued meanwhile. A
    // generated id is new to the broker: its first connect is clean already, and skipping the
    // extra round saves Paho's one-second pause between a disconnect and the next connect.
    if (!client_id.empty()) {
        wait_ok(cli.connect(connect_options_for(login, true)), "connect");
        wait_ok(cli.disconnect(), "disconnect");
    }

    auto resume = connect_options_for(login, false);
    resume.set_automatic_reconnect(std::chrono::seconds(1), std::chrono::seconds(1));
    wait_ok(cli.connect(resume), "connect");
    if (!filters.empty()) {
        wait_ok(impl_->subscribe(::mqtt::subscribe_options::SEND_RETAINED_ON_SUBSCRIBE),
                "subscribe");
    }
    impl_->subscribed_once = true;
}

MqttRecorder::~MqttRecorder() {
    try {
        auto& cli = impl_->client;
        cli.disable_callbacks();
        if (cli.is_connected()) {
            // End the session on the broker with the connection.
            ::mqtt::disconnect_options opts;
            if (impl_->version >= MQTTVERSION_5) {
                opts.set_properties(
                    ::mqtt::properties{{::mqtt::property::SESSION_EXPIRY_INTERVAL, 0}});
            }
            cli.disconnect(opts)->wait_for(std::chrono::seconds(2));
        }
    } catch (const ::mqtt::exception&) {
        // The broker may already be gone; nothing to clean up there.
    }
}

bool MqttRecorder::wait_for(const Predicate& pred, std::chrono::milliseconds timeout) {
    std::unique_lock lock(impl_->mutex);
    return impl_->cv.wait_for(lock, timeout, [&] { return pred(impl_->messages); });
}

std::optional<Received> MqttRecorder::wait_for_message(
    const std::string& topic, const std::function<bool(const std::string&)>& pred,
    std::chrono::milliseconds timeout, std::size_t from) {
    std::optional<Received> found;
    // Each message is looked at once: the predicate runs again on every arrival, and a rescan
    // from `from` each time costs quadratic time holding the lock the recording waits for,
    // which at thousands of messages a second on a loaded machine starves the recording.
    auto next = from;
    wait_for(
        [&](const std::vector<Received>& all) {
            for (; next < all.size(); ++next) {
                if (all[next].topic == topic && (!pred || pred(all[next].payload))) {
                    found = all[next];
                    return true;
                }
            }
            return false;
        },
        timeout);
    return found;
}

std::vector<Received> MqttRecorder::messages() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->messages;
}

std::vector<Received> MqttRecorder::messages_on(const std::string& topic) const {
    std::lock_guard lock(impl_->mutex);
    std::vector<Received> out;
    for (const auto& m : impl_->messages) {
        if (m.topic == topic) {
            out.push_back(m);
        }
    }
    return out;
}

bool MqttRecorder::connected() const { return impl_->client.is_connected(); }

std::size_t MqttRecorder::count() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->messages.size();
}

std::optional<Received> MqttRecorder::last(const std::string& topic) const {
    std::lock_guard lock(impl_->mutex);
    for (auto it = impl_->messages.rbegin(); it != impl_->messages.rend(); ++it) {
        if (it->topic == topic) {
            return *it;
        }
    }
    return std::nullopt;
}

void MqttRecorder::publish(const std::string& topic, const std::string& payload, bool retain) {
    auto tok = impl_->client.publish(topic, payload.data(), payload.size(), 1, retain);
    if (!tok->wait_for(kOperationTimeout)) {
        throw std::runtime_error("MqttRecorder: publish timed out");
    }
}

void MqttRecorder::publish_request(const std::string& topic, const std::string& payload,
                                   const std::string& response_topic,
                                   const std::string& correlation_data) {
    auto message = ::mqtt::make_message(topic, payload, 1, false);
    message->set_properties(::mqtt::properties{
        {::mqtt::property::RESPONSE_TOPIC, response_topic},
        {::mqtt::property::CORRELATION_DATA, correlation_data},
    });
    auto tok = impl_->client.publish(message);
    if (!tok->wait_for(kOperationTimeout)) {
        throw std::runtime_error("MqttRecorder: publish timed out");
    }
}

void MqttRecorder::publish_with_expiry(const std::string& topic, const std::string& payload,
                                       std::chrono::seconds expiry) {
    auto message = ::mqtt::make_message(topic, payload, 1, false);
    message->set_properties(::mqtt::properties{
        {::mqtt::property::MESSAGE_EXPIRY_INTERVAL, static_cast<int>(expiry.count())},
    });
    auto tok = impl_->client.publish(message);
    if (!tok->wait_for(kOperationTimeout)) {
        throw std::runtime_error("MqttRecorder: publish timed out");
    }
}

}  // namespace eip2mqtt::test
