// The redundancy section of the configuration: a hot-standby pair.

#include "adapters/yaml/detail/key_readers.hpp"
#include "adapters/yaml/detail/sections.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

namespace keys = core::config::keys;

constexpr KeyReader<RedundancySection> redundancy_rows[]{
    {"pair", [](KeyValue& v, RedundancySection& r) { return v.text_to(r.pair); }},
    {"takeover_ms",
     [](KeyValue& v, RedundancySection& r) {
         return v.integer_to<long long>(r.takeover, core::config::min_takeover_ms,
                                        core::config::max_takeover_ms);
     }},
    {"priority",
     [](KeyValue& v, RedundancySection& r) {
         const auto n = v.integer<int>(0, 65535);
         if (n) r.priority = *n;
         return n.has_value();
     }},
};
constexpr auto redundancy_readers = bind_keys(keys::redundancy, redundancy_rows);

}  // namespace

void read_redundancy(Reader& reader, const Node& node, const Mark& at, Config& config) {
    auto& redundancy = config.redundancy;
    redundancy.marks =
        reader.read_keys(node, at, "redundancy", "in redundancy", redundancy_readers, redundancy);
    if (!node.is_null() && node.is_defined() && !redundancy.marks.contains("pair")) {
        reader.error(redundancy.marks.node, "redundancy lacks 'pair' (the name both units share)");
    }
}

}  // namespace eip2mqtt::adapters::yaml::detail
