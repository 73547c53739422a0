#pragma once
// A fake Publisher (the MQTT client's seam): it keeps what it is given instead of sending it.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/adapters/mqtt/publisher.hpp"

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

}  // namespace eip2mqtt::test
