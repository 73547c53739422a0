// The check families that read payloads: seq, timestamps, and whether a payload decodes.

#include <string>

#include "tests/conformance/sparkplug_checks.hpp"

namespace eip2mqtt::test::conformance::checks {
namespace {

/// The node's Sparkplug messages of a connection, in order, but the NDEATH (outside seq).
std::vector<std::size_t> sequenced(const NodeView& view, const NodeConnection& c) {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < c.packets.size(); ++i) {
        const auto t = type_of(view, c.packets[i]);
        if (c.packets[i].from_node && !t.empty() && t != "NDEATH") out.push_back(i);
    }
    return out;
}

}  // namespace

Requirement has_seq(std::string_view tck_id, std::string_view type) {
    const std::string t(type);
    const bool wanted = t != "NDEATH";
    return {tck_id, Run::mqtt5,
            [t, wanted](const NodeView& view) {
                return each_sent(view, t, [&](const NodeConnection& c, std::size_t i) -> Verdict {
                    // Every type but NDEATH, which has none (its own check says so).
                    if (t.empty() && type_of(view, c.packets[i]) == "NDEATH") return std::nullopt;
                    const auto& payload = c.packets[i].payload;
                    if (!payload) return where(c, i) + ": not a Sparkplug payload";
                    if (payload->has_seq() != wanted) {
                        return where(c, i) + (wanted ? ": no seq" : ": a seq");
                    }
                    if (wanted && payload->seq() > 255) {
                        return where(c, i) + ": seq " + std::to_string(payload->seq());
                    }
                    if (t == "NBIRTH" && payload->seq() != 0) return where(c, i) + ": seq not 0";
                    return std::nullopt;
                });
            },
            [t, wanted](NodeView& view) {
                auto& payload = *first_sent(view, t).payload;
                if (wanted) {
                    payload.clear_seq();
                } else {
                    payload.set_seq(0);
                }
            }};
}

Requirement seq_one_more(std::string_view tck_id, std::string_view type) {
    const std::string t(type);
    return {tck_id, Run::mqtt5,
            [t](const NodeView& view) -> Verdict {
                for (const auto& c : view.connections) {
                    const auto order = sequenced(view, c);
                    for (std::size_t k = 1; k < order.size(); ++k) {
                        const auto& p = c.packets[order[k]];
                        const auto type = type_of(view, p);
                        // An NBIRTH starts seq again at 0 (has_seq judges it).
                        if (type == "NBIRTH" || (!t.empty() && type != t) || !p.payload) continue;
                        const auto& before = c.packets[order[k - 1]].payload;
                        if (!before) continue;
                        if (p.payload->seq() != (before->seq() + 1) % 256) {
                            return where(c, order[k]) + ": seq " +
                                   std::to_string(p.payload->seq()) + " after " +
                                   std::to_string(before->seq());
                        }
                    }
                }
                return std::nullopt;
            },
            [t](NodeView& view) {
                auto& payload = *first_sent(view, t).payload;
                payload.set_seq((payload.seq() + 7) % 256);
            }};
}

Requirement has_timestamp(std::string_view tck_id, std::string_view type) {
    const std::string t(type);
    return {tck_id, Run::mqtt5,
            [t](const NodeView& view) {
                return each_sent(view, t, [&](const NodeConnection& c, std::size_t i) -> Verdict {
                    const auto& payload = c.packets[i].payload;
                    if (!payload || !payload->has_timestamp())
                        return where(c, i) + ": no timestamp";
                    const auto ms = static_cast<std::int64_t>(payload->timestamp());
                    // UTC milliseconds of the run (a local time would be hours off).
                    if (ms < view.wall_from_ms || ms > view.wall_to_ms) {
                        return where(c, i) + ": timestamp " + std::to_string(ms) +
                               " outside the run's UTC span";
                    }
                    return std::nullopt;
                });
            },
            [t](NodeView& view) {
                auto& payload = *first_sent(view, t).payload;
                payload.set_timestamp(payload.timestamp() + 3600 * 1000);
            }};
}

Requirement decodes(std::string_view tck_id, std::string_view type) {
    const std::string t(type);
    return {tck_id, Run::mqtt5,
            [t](const NodeView& view) {
                return each_sent(view, t, [](const NodeConnection& c, std::size_t i) -> Verdict {
                    if (c.packets[i].payload) return std::nullopt;
                    return where(c, i) + ": not a Sparkplug B payload";
                });
            },
            [t](NodeView& view) { first_sent(view, t).payload.reset(); }};
}

}  // namespace eip2mqtt::test::conformance::checks
