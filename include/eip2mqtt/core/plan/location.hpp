#pragma once
/// Where in the plant a gateway, an exchange or a tag sits: the `location:` mapping (ISA-95's
/// enterprise, site, area, line, cell, asset, or any keys a plant uses), whose values fill the
/// placeholders of `mqtt.topic_template` (docs/configuration.md, "Topics and payloads").

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace eip2mqtt::core::plan {

struct Location {
    /// Each key with its value, in the order written. A handful per level: a flat vector.
    std::vector<std::pair<std::string, std::string>> levels;

    /// The value of `key`, or null when this level does not say (an empty value does say:
    /// it leaves the placeholder's level out, whatever a farther level says).
    const std::string* find(std::string_view key) const {
        for (const auto& [k, v] : levels) {
            if (k == key) return &v;
        }
        return nullptr;
    }
    bool empty() const { return levels.empty(); }

    friend bool operator==(const Location&, const Location&) = default;
};

}  // namespace eip2mqtt::core::plan
