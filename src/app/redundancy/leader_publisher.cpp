#include "eip2mqtt/app/redundancy/leader_publisher.hpp"

#include <utility>

namespace eip2mqtt::app::redundancy {

LeaderPublisher::LeaderPublisher(adapters::mqtt::Publisher& inner, std::function<bool()> leading)
    : inner_(inner), leading_(std::move(leading)) {}

void LeaderPublisher::publish(adapters::mqtt::Message&& message) {
    if (leading_()) return inner_.publish(std::move(message));
    message.clear();
}

void LeaderPublisher::set_subscriptions(std::vector<std::string> filters) {
    inner_.set_subscriptions(std::move(filters));
}

}  // namespace eip2mqtt::app::redundancy
