#pragma once
/// The Sparkplug node's way to its connection in a pair (docs/redundancy.md): publications pass
/// only while this unit leads. The edge node's session is the leader's alone, and a leader is
/// fenced from the instant its lease lapses (hung, or cut off from the broker), before its next
/// tick ends the session: what the node says meanwhile (its metrics' NDATA, a rebirth) is
/// dropped, as the FanOut drops what the exchanges say north.
///
/// Threading: the loop only.

#include <functional>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/mqtt/publisher.hpp"

namespace eip2mqtt::app::redundancy {

class LeaderPublisher final : public adapters::mqtt::Publisher {
public:
    /// `inner` (the node's connection) must outlive this; `leading` is asked at every
    /// publication.
    LeaderPublisher(adapters::mqtt::Publisher& inner, std::function<bool()> leading);

    void publish(adapters::mqtt::Message&& message) override;
    void set_subscriptions(std::vector<std::string> filters) override;

private:
    adapters::mqtt::Publisher& inner_;
    std::function<bool()> leading_;
};

}  // namespace eip2mqtt::app::redundancy
