#include "eip2mqtt/app/exchanges/write_log.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <variant>

#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/json_text.hpp"

namespace eip2mqtt::app {
namespace {

/// `NAME=value, …` of an accepted write (array elements as `NAME[i]`); empty for a refusal
/// decided before any tag was read.
std::string values_of(const WriteRequest& request) {
    const auto* write = std::get_if<ExchangeWrite>(&request.outcome);
    if (write == nullptr || write->producer == nullptr) return {};
    std::string out;
    for (const auto& tag : write->writes) {
        if (!out.empty()) out += ", ";
        const auto& tags = write->producer->tags;
        out += tag.tag_index < tags.size() ? tags[tag.tag_index].spec.name
                                           : "#" + std::to_string(tag.tag_index);
        if (tag.element) out += fmt::format("[{}]", *tag.element);
        out += '=' + core::plan::to_json(tag.value);
    }
    return out;
}

}  // namespace

std::uint64_t WriteLog::arrived(const WriteRequest& request, core::WallTime at) {
    if (entries_.size() == kept) entries_.pop_front();
    const auto id = next_id_++;
    entries_.push_back({id, core::to_ms(at), core::write::to_string(request.reply.via),
                        request.target, values_of(request), std::nullopt, 0});
    return id;
}

void WriteLog::answered(std::uint64_t id, std::string_view result, core::WallTime at) {
    // Ids grow with the entries: a binary search finds one among the kept.
    const auto found = std::lower_bound(entries_.begin(), entries_.end(), id,
                                        [](const Entry& e, std::uint64_t i) { return e.id < i; });
    // A later result replaces an earlier one: a left write settled on taking the lead.
    if (found == entries_.end() || found->id != id) return;
    found->result = std::string(result);
    found->answered_ms = core::to_ms(at);
}

void WriteLog::append_json(std::string& out) const {
    out += '[';
    for (auto it = entries_.rbegin(); it != entries_.rend(); ++it) {
        if (it != entries_.rbegin()) out += ',';
        fmt::format_to(std::back_inserter(out), R"({{"id":{},"time":{},"origin":")", it->id,
                       it->at_ms);
        out += it->origin;
        out += R"(","target":)";
        core::append_json_string(out, it->target);
        out += R"(,"values":)";
        core::append_json_string(out, it->values);
        out += R"(,"result":)";
        if (it->result) {
            core::append_json_string(out, *it->result);
            fmt::format_to(std::back_inserter(out), R"(,"answered_at":{}}})", it->answered_ms);
        } else {
            out += "null}";
        }
    }
    out += ']';
}

}  // namespace eip2mqtt::app
