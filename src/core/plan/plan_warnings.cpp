#include "eip2mqtt/core/plan/plan_warnings.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <unordered_map>

#include "core/detail/lower.hpp"

namespace eip2mqtt::core::plan {
namespace {

using detail::lower;

/// The tags whose names differ only in case from an earlier one: their topics differ, yet a
/// case-blind historian or database (SQL Server's default collation, many tag databases)
/// merges them into one series.
void case_twins(const ExchangePlan& plan, std::vector<std::string>& warnings) {
    std::unordered_map<std::string, const std::string*> first_by_lower;
    first_by_lower.reserve(plan.tags.size());
    for (const auto& tag : plan.tags) {
        const auto [it, added] = first_by_lower.emplace(lower(tag.spec.name), &tag.spec.name);
        if (added || *it->second == tag.spec.name) continue;
        warnings.push_back("tags " + *it->second + " and " + tag.spec.name +
                           " differ only in case: a case-blind historian or database merges "
                           "them into one series; rename one");
    }
}

}  // namespace

std::vector<std::string> plan_warnings(const ExchangePlan& plan, const WarningContext& context) {
    std::vector<std::string> warnings;
    const bool consumed = plan.spec.direction == Direction::consume;
    if (consumed && plan.timeout.count() == 0) {
        // A restart is recognised by the producer's time moving forward while its request ids
        // went back; without timestamps only the update timeout resynchronises.
        warnings.push_back(
            "timeout_ms is 0: if its producer sends no timestamps, after a restart of the "
            "producer every datagram is dropped as out of order until its request ids pass "
            "the last one seen (up to 32,768 datagrams); keep an update timeout (the default "
            "is 3 periods)");
    }
    if (consumed && !plan.spec.length && !plan.tags.empty()) {
        // The producer's datagrams are often longer than the last tag configured (spare bytes,
        // tags not mapped yet), and a datagram of another length is refused.
        warnings.push_back("length is not set: assumed " + std::to_string(plan.length) +
                           " bytes, the end of the last tag; a datagram of any other length is "
                           "refused (counted as length_mismatches in _status): set length to "
                           "what the producer sends (`sniff` shows it)");
    }
    case_twins(plan, warnings);
    if (context.mqtt_3_1_1 && plan.topic.find('.') != std::string::npos) {
        warnings.push_back("topic " + plan.topic +
                           " has dots: some MQTT 3.1.1 brokers (RabbitMQ) turn each into a "
                           "level separator, so subscribers must use another topic than the "
                           "one shown here (docs/brokers.md); prefer - or _");
    }
    return warnings;
}

}  // namespace eip2mqtt::core::plan
