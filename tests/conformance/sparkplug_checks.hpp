#pragma once
/// The building blocks of the Sparkplug conformance checks (sparkplug_requirements.hpp): walks
/// over what the node sent or was handed, and the families of checks several tck-ids share
/// (one per message type), each with the alteration that breaks it.

#include <chrono>
#include <functional>
#include <string>
#include <string_view>

#include "tests/conformance/sparkplug_requirements.hpp"

namespace eip2mqtt::test::conformance::checks {

/// What the node may still send after a message that stops its DATA (an offline STATE, a
/// rebirth request): what it had made before it read the message, and the relay reads it
/// later. The relay's clock cannot tell when the node read it; half a second covers what was
/// on its way on a loaded machine, and no DATA made after it could pass as such for long.
inline constexpr std::chrono::milliseconds in_flight{500};

/// Where a packet is, for a verdict: "connection 2 (broker 1), packet 14 (DDATA ...)".
std::string where(const NodeConnection& connection, std::size_t packet);

/// Calls `f` on each PUBLISH the node sent whose type is `type` (any type when empty), in
/// order, until one says what breaks the requirement.
Verdict each_sent(const NodeView& view, std::string_view type,
                  const std::function<Verdict(const NodeConnection&, std::size_t)>& f);
/// The first PUBLISH the node sent of `type` (empty: of any type in seq, not NDEATH), for an
/// alteration; throws when there is none.
NodePacket& first_sent(NodeView& view, std::string_view type);
/// The message type of a packet of `view`'s node ("NBIRTH"...); empty for another.
std::string type_of(const NodeView& view, const NodePacket& packet);
bool is_data(std::string_view type);  ///< NDATA or DDATA
/// The device element of a device topic ("line" of .../DDATA/gw1/line); empty for none.
std::string device_of(const NodeView& view, const std::string& topic_name);
/// A STATE delivered to the node: the primary host's topic, online, timestamp.
struct State {
    std::string host;
    bool online = false;
    std::int64_t timestamp = -1;
};
std::optional<State> state_of(const NodePacket& packet);
/// An NCMD delivered to the node asking for a rebirth (typed or not).
bool is_rebirth_request(const NodeView& view, const NodePacket& packet);

// --- families: a check and its alteration for each message type (empty: every type) -----
Requirement qos0_not_retained(std::string_view tck_id, std::string_view type);
Requirement topic_of_type(std::string_view tck_id, std::string_view type);
Requirement has_seq(std::string_view tck_id, std::string_view type);
Requirement seq_one_more(std::string_view tck_id, std::string_view type);
Requirement has_timestamp(std::string_view tck_id, std::string_view type);
Requirement decodes(std::string_view tck_id, std::string_view type);

}  // namespace eip2mqtt::test::conformance::checks
