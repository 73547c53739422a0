#include "eip2mqtt/app/redundancy/section_summary.hpp"

#include <sstream>

namespace eip2mqtt::app::redundancy {

std::string section_summary(const core::config::RedundancySection& section) {
    if (!section.enabled()) return {};
    std::ostringstream out;
    out << "redundancy: pair " << section.pair << ", takeover after " << section.takeover.count()
        << " ms, the lease renewed every " << (section.takeover / 4).count() << " ms"
        << (section.priority ? ", priority " + std::to_string(*section.priority) : std::string())
        << "\n";
    return out.str();
}

}  // namespace eip2mqtt::app::redundancy
