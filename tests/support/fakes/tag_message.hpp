#pragma once
// A publication of one tag, retained or not: what a role's fence on a connection (may_send) is
// asked about in the pair's and the role's tests.

#include "eip2mqtt/adapters/mqtt/message.hpp"

namespace eip2mqtt::test {

inline adapters::mqtt::Message tag_message(bool retain) {
    adapters::mqtt::Message m;
    m.topic = "acme/turbine/e1/speed";
    m.retain = retain;
    return m;
}

}  // namespace eip2mqtt::test
