// The loader's run: parse, read each section, validate, sort the diagnostics.

#include "adapters/yaml/detail/loader.hpp"

#include <algorithm>
#include <optional>
#include <string_view>
#include <tuple>
#include <utility>

#include "adapters/yaml/detail/sections.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

/// The top level's keys: the sections.
constexpr std::array<std::string_view, 7> top_keys{"gateway",   "mqtt",       "eip",      "metrics",
                                                   "sparkplug", "redundancy", "exchanges"};

/// The 1-based line and column of the first tab in a line's indentation, up to line `last`
/// (0-based, where the parser stopped) and the line after it; blank lines do not count.
std::optional<std::pair<int, int>> first_indenting_tab(std::string_view text, int last) {
    int line = 0;
    for (std::size_t start = 0; start <= text.size() && line <= last + 1; ++line) {
        const auto end = std::min(text.find('\n', start), text.size());
        const auto indent = text.find_first_not_of(" \t", start);
        const auto tab = text.find('\t', start);
        if (indent < end && tab < indent) {
            return std::pair{line + 1, static_cast<int>(tab - start) + 1};
        }
        start = end + 1;
    }
    return std::nullopt;
}

/// The 1-based line and column of the first NUL byte. YAML allows none (YAML 1.2 §5.1,
/// c-printable); yaml-cpp reads one as the end of a token and says something else further on
/// ("bad character found while scanning hex number"), so it is named where it is.
std::optional<std::pair<int, int>> first_nul(std::string_view text) {
    const auto nul = text.find('\0');
    if (nul == std::string_view::npos) return std::nullopt;
    const auto before = text.substr(0, nul);
    const auto line = std::count(before.begin(), before.end(), '\n') + 1;
    const auto line_start = before.rfind('\n');
    const auto column = line_start == std::string_view::npos ? nul + 1 : nul - line_start;
    return std::pair{static_cast<int>(line), static_cast<int>(column)};
}

}  // namespace

core::Result<Config, Diagnostics> Loader::load(const std::string& text) {
    Config config;
    config.file = file_;
    const auto cancelled = [this] {
        reader_.error({file_, 0, 0}, "the load was given up: the gateway is stopping");
        return core::fail(std::move(diagnostics_));
    };
    if (const auto nul = first_nul(text)) {
        reader_.error({file_, nul->first, nul->second},
                      "YAML syntax error: a NUL byte (\\x00) in the file; YAML allows none");
        return core::fail(std::move(diagnostics_));
    }
    try {
        const Tree tree = Tree::parse(text, stop_);
        if (stop_.stop_requested()) return cancelled();
        const Node root = tree.root();
        if (!root.is_defined() || root.is_null()) {
            reader_.error({file_, 1, 1}, "the configuration is empty");
            return core::fail(std::move(diagnostics_));
        }
        if (!root.is_map()) {
            reader_.error(reader_.mark(root), "expected a mapping at the top level");
        } else {
            read_root(root, config);
        }
    } catch (const YAML::Exception& e) {
        // yaml-cpp's words for a tab ("illegal map value", "end of map not found") never say
        // tab, and a tab looks like spaces in most editors: name it.
        if (const auto tab = first_indenting_tab(text, e.mark.line + 1)) {
            reader_.error(
                {file_, tab->first, tab->second},
                "YAML syntax error: this line is indented with a tab; YAML indents with spaces "
                "only (the parser said: " +
                    e.msg + ")");
        } else {
            reader_.error(reader_.mark(e.mark), "YAML syntax error: " + e.msg);
        }
        return core::fail(std::move(diagnostics_));
    } catch (const Tree::Cancelled&) {
        return cancelled();
    }
    if (stop_.stop_requested()) return cancelled();
    if (config.mqtt.client_id.empty()) config.mqtt.client_id = "eip2mqtt-" + config.gateway.id;
    // Semantic checks also run after local errors so that one run shows every problem;
    // entities whose own keys failed to parse were left out of the model to avoid echoes.
    auto semantic = core::config::validate(config);
    diagnostics_.insert(diagnostics_.end(), std::make_move_iterator(semantic.begin()),
                        std::make_move_iterator(semantic.end()));
    if (diagnostics_.empty()) return config;
    std::stable_sort(
        diagnostics_.begin(), diagnostics_.end(), [this](const Diagnostic& a, const Diagnostic& b) {
            return std::make_tuple(a.mark.file != file_, a.mark.file, a.mark.line, a.mark.column) <
                   std::make_tuple(b.mark.file != file_, b.mark.file, b.mark.line, b.mark.column);
        });
    return core::fail(std::move(diagnostics_));
}

void Loader::read_root(const Node& root, Config& config) {
    reader_.walk(root, reader_.mark(root), "configuration", "at the top level", top_keys,
                 [&](const std::string& key, const Node& value, const Mark& at) {
                     if (key == "gateway") read_gateway(reader_, value, at, config);
                     if (key == "mqtt") read_mqtt(reader_, value, at, config);
                     if (key == "eip") read_eip(reader_, value, at, config);
                     if (key == "metrics") read_metrics(reader_, value, at, config);
                     if (key == "sparkplug") read_sparkplug(reader_, value, at, config);
                     if (key == "redundancy") read_redundancy(reader_, value, at, config);
                     if (key == "exchanges")
                         read_exchanges(reader_, point_lists_, value, at, config);
                 });
}

}  // namespace eip2mqtt::adapters::yaml::detail
