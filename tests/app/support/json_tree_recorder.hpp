#pragma once
// The JSON topic tree over a recording publisher: what the exchanges report becomes the MQTT
// messages the gateway would publish, kept for a test to read.

#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/app/northbound/json_tree/json_tree.hpp"
#include "tests/support/fakes/recording_publisher.hpp"

namespace eip2mqtt::test {

/// JsonTree publishing to a RecordingPublisher; the writes it decodes are kept, not staged.
class JsonTreeRecorder final : public app::WriteHandler {
public:
    explicit JsonTreeRecorder(app::northbound::json_tree::PublishSettings settings = {},
                              RecordingPublisher::Mode mode = RecordingPublisher::Mode::keep_all,
                              std::string base_topic = "")
        : publisher(mode),
          uns_({settings, {std::move(base_topic), false}, "_gateway/test/metrics"}, publisher,
               *this) {}

    void on_write(app::WriteRequest&& request) override { writes.push_back(std::move(request)); }
    app::northbound::json_tree::JsonTree& northbound() { return uns_; }

    RecordingPublisher publisher;
    std::vector<app::WriteRequest> writes;

private:
    app::northbound::json_tree::JsonTree uns_;
};

}  // namespace eip2mqtt::test
