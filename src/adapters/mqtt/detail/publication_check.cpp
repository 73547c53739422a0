#include "adapters/mqtt/detail/publication_check.hpp"

#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::adapters::mqtt::detail {
namespace {

constexpr std::size_t max_correlation_data = 65535;

}  // namespace

std::string publication_problem(const Message& message, std::size_t max_packet_size) {
    if (auto problem = core::plan::topic_name_problem(message.topic); !problem.empty()) {
        return "topic " + problem;
    }
    if (message.correlation_data.size() > max_correlation_data) {
        return "correlation data of " + std::to_string(message.correlation_data.size()) +
               " bytes (MQTT allows 65535)";
    }
    const std::size_t size = publish_packet_bytes(message);
    if (size > max_packet_size) {
        return "a packet of up to " + std::to_string(size) + " bytes (the broker takes " +
               std::to_string(max_packet_size) + ")";
    }
    return {};
}

}  // namespace eip2mqtt::adapters::mqtt::detail
