#pragma once
/// A JSON tree's publisher on a connection whose base_topic is not the first connection's
/// (core/plan/topic_rebase.hpp): every topic and filter goes out under the connection's own
/// base; what the connection hears comes back under the first's, as the plans know it.
///
/// Threading: the loop only.

#include <utility>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/core/plan/topic_rebase.hpp"

namespace eip2mqtt::app::northbound::json_tree {

class RebasedPublisher final : public adapters::mqtt::Publisher {
public:
    /// `inner` must outlive it.
    RebasedPublisher(adapters::mqtt::Publisher& inner, core::plan::TopicRebase rebase)
        : inner_(inner), rebase_(std::move(rebase)) {}

    void publish(adapters::mqtt::Message&& message) override {
        rebase_.outward(message.topic);
        inner_.publish(std::move(message));
    }
    void set_subscriptions(std::vector<std::string> filters) override {
        for (auto& filter : filters) rebase_.outward(filter);
        inner_.set_subscriptions(std::move(filters));
    }

    /// `message` as the plans know it: its topic and response topic under the first base.
    adapters::mqtt::Incoming inward(adapters::mqtt::Incoming message) const {
        rebase_.inward(message.topic);
        rebase_.inward(message.response_topic);
        return message;
    }

private:
    adapters::mqtt::Publisher& inner_;
    core::plan::TopicRebase rebase_;
};

}  // namespace eip2mqtt::app::northbound::json_tree
