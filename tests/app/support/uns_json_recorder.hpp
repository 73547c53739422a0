#pragma once
// The JSON topic tree over a recording publisher: what the exchanges report becomes the MQTT
// messages the gateway would publish, kept for a test to read.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/northbound/json_tree/uns_json.hpp"

namespace eip2mqtt::test {

/// A Publisher that keeps what it is given: every message, or (keep_last) only the last one,
/// handing back the buffers of the one before as the MQTT client does, so that a data path
/// under test allocates nothing.
class RecordingPublisher final : public adapters::mqtt::Publisher {
public:
    enum class Mode { keep_all, keep_last };
    explicit RecordingPublisher(Mode mode = Mode::keep_all) : mode_(mode) {}

    void publish(adapters::mqtt::Message&& message) override {
        ++count;
        if (mode_ == Mode::keep_last) {
            std::swap(last, message);
        } else {
            published.push_back(std::move(message));
        }
        message.clear();
    }
    void set_subscriptions(std::vector<std::string> filters) override {
        subscriptions = std::move(filters);
    }

    /// The payloads published on `topic`, in order (keep_all).
    std::vector<std::string> on(const std::string& topic) const {
        std::vector<std::string> payloads;
        for (const auto& m : published) {
            if (m.topic == topic) payloads.push_back(m.payload);
        }
        return payloads;
    }

    std::vector<adapters::mqtt::Message> published;  ///< keep_all
    adapters::mqtt::Message last;                    ///< keep_last
    std::size_t count = 0;
    std::vector<std::string> subscriptions;

private:
    Mode mode_;
};

/// UnsJson publishing to a RecordingPublisher; the writes it decodes are kept, not staged.
class UnsJsonRecorder final : public app::WriteHandler {
public:
    explicit UnsJsonRecorder(app::northbound::json_tree::PublishSettings settings = {},
                             RecordingPublisher::Mode mode = RecordingPublisher::Mode::keep_all,
                             std::string base_topic = "")
        : publisher(mode),
          uns_({settings, {std::move(base_topic), false}, "_gateway/test/metrics"}, publisher,
               *this) {}

    void on_write(app::WriteRequest&& request) override { writes.push_back(std::move(request)); }
    app::northbound::json_tree::UnsJson& northbound() { return uns_; }

    RecordingPublisher publisher;
    std::vector<app::WriteRequest> writes;

private:
    app::northbound::json_tree::UnsJson uns_;
};

}  // namespace eip2mqtt::test
