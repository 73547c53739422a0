#pragma once
/// What every reader of the configuration's sections shares: the marks of one file's YAML tree,
/// the list its problems go to, the walk of a mapping's keys and the scalar readers, each
/// reporting a value that does not read at its line and column.
///
/// Module-private to src/adapters/yaml.

#include <yaml-cpp/exceptions.h>

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "adapters/yaml/detail/scalar_text.hpp"
#include "adapters/yaml/detail/tree.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/config_keys.hpp"

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
using core::config::MetricsAuth;
using core::config::MetricsSection;
using core::config::MetricsTls;
using core::config::MqttSection;
using core::config::RedundancySection;
using core::config::SparkplugSection;
using core::config::StoreAndForwardSection;
using core::config::TagConfig;
using core::config::TlsSection;
using core::plan::Direction;
using core::plan::TagType;

class KeyValue;
template <class Into, std::size_t N>
struct KeyReaders;

/// For a walk whose keys' failures leave nothing out (a section's).
struct IgnoreFailure {
    void operator()(std::string_view /*key*/) const {}
};

/// Reads the values of one file's YAML tree into the configuration model, reporting each
/// problem into the diagnostics it is given, at the mark of what it read.
class Reader {
public:
    Reader(FileName file, Diagnostics& diagnostics)
        : file_(std::move(file)), diagnostics_(diagnostics) {}

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

    /// Adds problems found elsewhere (a point list's) to those of the file.
    void report(const Diagnostics& found) {
        diagnostics_.insert(diagnostics_.end(), found.begin(), found.end());
    }

private:
    FileName file_;  ///< shared by every mark of the file
    Diagnostics& diagnostics_;
};

}  // namespace eip2mqtt::adapters::yaml::detail
