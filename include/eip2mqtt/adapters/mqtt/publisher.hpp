#pragma once
/// What a northbound needs of an MQTT connection: publish, and say what to subscribe to. The
/// Client implements it; tests record what goes through it.

#include <string>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"

namespace eip2mqtt::adapters::mqtt {

class Publisher {
public:
    virtual ~Publisher() = default;
    /// Queues a publication and leaves `message` blank (Message::clear()), often with the
    /// buffers of an earlier publication, so that a caller filling the same Message again
    /// allocates nothing.
    virtual void publish(Message&& message) = 0;
    /// Topic filters subscribed on every connect; may be changed at any time.
    virtual void set_subscriptions(std::vector<std::string> filters) = 0;
};

}  // namespace eip2mqtt::adapters::mqtt
