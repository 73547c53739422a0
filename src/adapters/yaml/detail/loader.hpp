#pragma once
/// The configuration loader: walks the YAML tree section by section, records the mark of every
/// key for diagnostics, and reports every problem of the file in one run. Its reading is in
/// four files: loader.cpp (the run and scalars), read_sections.cpp (gateway, mqtt, eip,
/// metrics, sparkplug), read_redundancy.cpp and read_exchanges.cpp (exchanges, tags and point
/// lists), the last three with the tables that bind each key of a mapping to its field
/// (key_readers.hpp).
///
/// Module-private to src/adapters/yaml.

#include <yaml-cpp/exceptions.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <type_traits>

#include "adapters/yaml/detail/scalar_text.hpp"
#include "adapters/yaml/detail/tree.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/core/config/config_keys.hpp"
#include "eip2mqtt/core/config/point_index.hpp"
#include "eip2mqtt/core/config/point_list.hpp"

namespace eip2mqtt::adapters::yaml::detail {

using core::config::Config;
using core::config::Diagnostic;
using core::config::Diagnostics;
using core::config::ExchangeConfig;
using core::config::FileName;
using core::config::GatewaySection;
using core::config::in_quotes;
using core::config::Mark;
using core::config::Marks;
using core::config::MetricsSection;
using core::config::MqttSection;
using core::config::RedundancySection;
using core::config::SparkplugSection;
using core::config::StoreAndForwardSection;
using core::config::TagConfig;
using core::config::TlsSection;
using core::plan::Direction;
using core::plan::TagType;

// The keys of each mapping are those of core/config/config_keys.hpp, where each has its reload
// rule; the top level's are the sections. The mappings read through a table of key readers
// (key_readers.hpp) take their keys from it.
inline constexpr std::array<std::string_view, 7> top_keys{
    "gateway", "mqtt", "eip", "metrics", "sparkplug", "redundancy", "exchanges"};
inline constexpr auto eip_keys = core::config::keys::names(core::config::keys::eip);
inline constexpr auto multicast_keys = core::config::keys::names(core::config::keys::multicast);
inline constexpr auto commands_keys = core::config::keys::names(core::config::keys::commands);

/// An exchange while its keys are read.
struct ExchangeDraft {
    core::plan::ExchangeSpec& spec;
    std::string label;    ///< how messages name it
    bool broken = false;  ///< an identity key is missing or bad: leave it out of the model
    std::optional<Node> tags_node;
    std::string points;
    bool topic_written = false;
};

/// A tag while its keys are read.
struct TagDraft {
    core::plan::TagSpec& spec;
    bool broken = false;  ///< a value failed to parse: leave the tag out of the model
    std::optional<Node> initial;
    Mark initial_mark;
};

class KeyValue;
template <class Into, std::size_t N>
struct KeyReaders;

/// For a walk whose keys' failures leave nothing out (a section's).
struct IgnoreFailure {
    void operator()(std::string_view /*key*/) const {}
};

class Loader {
public:
    /// `stop`: the load gives up, with one diagnostic, soon after it is requested.
    explicit Loader(std::string file, std::stop_token stop = {})
        : file_(std::move(file)),
          dir_(std::filesystem::path(file_.str()).parent_path()),
          stop_(std::move(stop)) {}

    core::Result<Config, Diagnostics> load(const std::string& text);

private:
    friend class KeyValue;

    Mark mark(const YAML::Mark& m) const {
        if (m.is_null()) return {file_, 0, 0};
        return {file_, m.line + 1, m.column + 1};
    }
    Mark mark(const Node& node) const { return mark(node.mark()); }

    void error(const Mark& at, std::string message) {
        diagnostics_.push_back({at, std::move(message)});
    }

    /// Walks a mapping: reports unknown and repeated keys, records every key's mark, and hands
    /// each known key to `handle(key, value, mark)`. `where` completes "unknown key 'x' in ...":
    /// a string, or a callable that makes it only for a message (a tag's, built for each of
    /// 100,000 tags, cost two heap strings a tag for errors that mostly never come). Templates,
    /// not std::function: a handler capturing a tag's state would be a heap block per tag too.
    template <class Where, class Handle>
    Marks walk(const Node& node, const Mark& at, const std::string& what, const Where& where,
               Keys allowed, const Handle& handle) {
        return walk_indexed(node, at, what, where, allowed,
                            [&](std::size_t, const std::string& key, const Node& value,
                                const Mark& k) { handle(key, value, k); });
    }

    /// walk(), telling `handle(index, key, value, mark)` the key's index in `allowed` too.
    template <class Where, class Handle>
    Marks walk_indexed(const Node& node, const Mark& at, const std::string& what,
                       const Where& where, Keys allowed, const Handle& handle) {
        const auto where_text = [&]() -> std::string {
            if constexpr (std::is_invocable_v<const Where&>) {
                return where();
            } else {
                return where;
            }
        };
        Marks marks;
        marks.node = node.is_defined() && !node.is_null() ? mark(node) : at;
        if (!node.is_defined() || node.is_null()) return marks;
        if (!node.is_map()) {
            error(at, "expected a mapping for " + in_quotes(what));
            return marks;
        }
        marks.keys.reserve(node.size());
        for (std::size_t i = 0; i < node.size(); ++i) {
            const Node key_node = node.key(i);
            const Mark key_mark = mark(key_node);
            if (!key_node.is_scalar()) {
                error(key_mark, "expected a plain key " + where_text());
                continue;
            }
            const std::string key(key_node.scalar());
            const auto found = std::find(allowed.begin(), allowed.end(), key);
            if (found == allowed.end()) {
                std::string message = "unknown key " + in_quotes(key) + " " + where_text();
                if (const auto close = suggestion(key, allowed)) {
                    message += " (did you mean " + in_quotes(*close) + "?)";
                }
                error(key_mark, std::move(message));
                continue;
            }
            if (!marks.add(key, key_mark)) {
                error(key_mark, "duplicate key " + in_quotes(key) + " " + where_text());
                continue;
            }
            handle(static_cast<std::size_t>(found - allowed.begin()), key, node.value(i), key_mark);
        }
        return marks;
    }

    /// Walks a mapping whose keys `readers` (key_readers.hpp) read into `into`, as walk() does;
    /// `failed(key)` is told each key whose value did not read.
    template <class Into, std::size_t N, class Where, class Failed = IgnoreFailure>
    Marks read_keys(const Node& node, const Mark& at, const std::string& what, const Where& where,
                    const KeyReaders<Into, N>& readers, Into& into,
                    const Failed& failed = Failed{});

    // --- scalars ------------------------------------------------------------------------------

    /// A string value read by `parse` (returning an optional); one that does not parse is
    /// reported as "<key> '<text>' <problem>" (text() reports a value that is no string).
    template <class Parse>
    auto parsed(const Node& value, const std::string& key, const Mark& at, Parse parse,
                std::string_view problem) -> decltype(parse(std::string_view())) {
        const auto s = text(value, key, at);
        if (!s) return std::nullopt;
        auto result = parse(*s);
        if (!result) error(at, key + " " + in_quotes(*s) + " " + std::string(problem));
        return result;
    }

    std::optional<std::string> text(const Node& value, const std::string& key, const Mark& at);

    template <class T>
    std::optional<T> integer(const Node& value, const std::string& key, const Mark& at,
                             T min = std::numeric_limits<T>::min(),
                             T max = std::numeric_limits<T>::max()) {
        const auto parsed =
            value.is_scalar() ? parse_integer<long long>(value.scalar()) : std::nullopt;
        if (!parsed) {
            error(at, "expected an integer for " + in_quotes(key));
            return std::nullopt;
        }
        if (*parsed < static_cast<long long>(min) ||
            (*parsed > 0 &&
             static_cast<unsigned long long>(*parsed) > static_cast<unsigned long long>(max))) {
            error(at, in_quotes(key) + " " + std::to_string(*parsed) + " is outside " +
                          std::to_string(min) + ".." + std::to_string(max));
            return std::nullopt;
        }
        return static_cast<T>(*parsed);
    }

    std::optional<core::plan::TimestampSource> timestamp_source(const Node& value,
                                                                const std::string& key,
                                                                const Mark& at);

    std::optional<double> number(const Node& value, const std::string& key, const Mark& at) {
        const auto parsed = value.is_scalar() ? parse_double(value.scalar()) : std::nullopt;
        if (!parsed) error(at, "expected a number for " + in_quotes(key));
        return parsed;
    }

    std::optional<bool> boolean(const Node& value, const std::string& key, const Mark& at);

    // --- sections -----------------------------------------------------------------------------

    void read_root(const Node& root, Config& config);

    void read_gateway(const Node& node, const Mark& at, Config& config);

    void read_mqtt(const Node& node, const Mark& at, Config& config);

    void read_eip(const Node& node, const Mark& at, Config& config);
    void read_commands(const Node& node, const Mark& at, Config& config);
    /// A list of IPv4 subnets (`eip.commands.allow`, `trusted`); each bad item an error.
    std::vector<core::net::Subnet> subnets(const Node& value, const std::string& key,
                                           const Mark& at);
    void read_multicast(const Node& node, const Mark& at, core::config::EipSection& eip);

    void read_metrics(const Node& node, const Mark& at, Config& config);
    void read_sparkplug(const Node& node, const Mark& at, Config& config);
    void read_redundancy(const Node& node, const Mark& at, Config& config);

    void read_exchanges(const Node& node, const Mark& at, Config& config);

    void read_exchange(const Node& node, int index, Config& config);

    std::optional<TagConfig> read_tag(const Node& node, const std::string& exchange_label);

    /// `initial` as the tag's type holds it. Out-of-range values are kept (as int64 or double)
    /// for validate() to report against the type's range.
    std::optional<core::plan::Value> read_initial(const Node& value, TagType type, const Mark& at);

    /// docs/protocol.md §6: the rows of the point list whose Node is this exchange.
    void read_points(const std::string& points, ExchangeConfig& exchange);

    /// A point list read once for all the exchanges that name it, with its rows by Node.
    struct LoadedPoints {
        explicit LoadedPoints(core::config::PointList parsed)
            : list(std::move(parsed)), index(list) {}
        core::config::PointList list;
        core::config::PointIndex index;  ///< views into `list`: both live and die together
    };

    FileName file_;  ///< shared by every mark of the file
    std::filesystem::path dir_;
    std::stop_token stop_;
    Diagnostics diagnostics_;
    std::map<std::string, std::unique_ptr<LoadedPoints>> point_lists_;  ///< null: unreadable
};

}  // namespace eip2mqtt::adapters::yaml::detail
