#include "eip2mqtt/core/config/config.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <string_view>
#include <tuple>
#include <utility>
#include <variant>

#include "core/config/detail/config_names.hpp"
#include "core/config/detail/sparkplug_check.hpp"
#include "core/config/detail/topic_collisions.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/topic_rules.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::config {

namespace {

auto find_key(const std::vector<std::pair<std::string, Mark>>& keys, std::string_view key) {
    return std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.first == key; });
}

}  // namespace

const Mark& Marks::of(std::string_view key) const {
    const auto it = find_key(keys, key);
    return it == keys.end() ? node : it->second;
}

bool Marks::contains(std::string_view key) const { return find_key(keys, key) != keys.end(); }

bool Marks::add(std::string_view key, const Mark& at) {
    if (contains(key)) return false;
    keys.emplace_back(key, at);
    return true;
}

namespace {

using detail::tag_name_problem;
using detail::topic_problem;
using plan::Direction;
using plan::TagType;

constexpr long long min_period_ms = 2;        // docs/protocol.md §5
constexpr long long max_period_ms = 3600000;  // docs/protocol.md §5
/// MQTT encodes the length of a string (a client id) in two bytes, as a topic's.
constexpr std::size_t max_string_bytes = plan::max_topic_bytes;

// The fixed parts of the longest topics the gateway builds: {base}/{topic}/set/result for an
// exchange (longer than its /_status and /_values), {base}/{topic}/{tag}/set/result for a tag,
// {base}/_gateway/{id}/metrics for the gateway (longer than /state). Their lengths are added
// up, the topics never built: a configuration may hold 100,000 tags.
constexpr std::string_view result_suffix = "/set/result";
constexpr std::string_view gateway_level = "/_gateway/";
constexpr std::string_view metrics_suffix = "/metrics";

/// "makes topic '{pattern}' N bytes long (MQTT allows 65535)".
std::string too_long(std::string_view pattern, std::size_t bytes) {
    return "makes topic '" + std::string(pattern) + "' " + std::to_string(bytes) +
           " bytes long (MQTT allows " + std::to_string(plan::max_topic_bytes) + ")";
}

std::string format_number(double value) {
    std::string text = std::to_string(value);
    if (text.find('.') != std::string::npos) {
        text.erase(text.find_last_not_of('0') + 1);
        if (text.back() == '.') text.pop_back();
    }
    return text;
}

double as_double(const plan::Value& value) {
    return std::visit([](auto v) { return static_cast<double>(v); }, value);
}

class Validator {
public:
    explicit Validator(const Config& config) : config_(config) {}

    Diagnostics run() {
        check_gateway();
        check_mqtt();
        check_gateway_topics();
        check_exchanges();
        detail::check_sparkplug(config_, out_);
        std::stable_sort(
            out_.begin(), out_.end(), [this](const Diagnostic& a, const Diagnostic& b) {
                return std::make_tuple(a.mark.file != config_.file, a.mark.file, a.mark.line,
                                       a.mark.column) < std::make_tuple(b.mark.file != config_.file,
                                                                        b.mark.file, b.mark.line,
                                                                        b.mark.column);
            });
        return std::move(out_);
    }

private:
    void error(const Mark& mark, std::string message) {
        out_.push_back({mark, std::move(message)});
    }

    void check_gateway() {
        const auto& gateway = config_.gateway;
        id_ok_ = false;
        if (gateway.id.empty()) {
            error(gateway.marks.of("id"), "gateway id is empty");
        } else if (gateway.id.find_first_of("/+#") != std::string::npos) {
            error(gateway.marks.of("id"), "gateway id " + in_quotes(gateway.id) +
                                              " contains '/', '+' or '#' (it is a topic level)");
        } else if (const auto problem = plan::text_problem(gateway.id); !problem.empty()) {
            error(gateway.marks.of("id"), "gateway id " + in_quotes(gateway.id) + " " +
                                              std::string(problem) + " (it is a topic level)");
        } else {
            id_ok_ = true;
        }
        static constexpr std::array<std::string_view, 7> levels{"trace", "debug",    "info", "warn",
                                                                "error", "critical", "off"};
        if (std::find(levels.begin(), levels.end(), gateway.log_level) == levels.end()) {
            error(gateway.marks.of("log_level"),
                  "log_level " + in_quotes(gateway.log_level) +
                      " is not one of trace, debug, info, warn, error, critical, off");
        }
    }

    void check_mqtt() {
        const auto& mqtt = config_.mqtt;
        if (mqtt.version != 5 && mqtt.version != 3) {
            error(mqtt.marks.of("version"), "mqtt version must be 5 or 3.1.1");
        }
        if (mqtt.qos < 0 || mqtt.qos > 2) {
            error(mqtt.marks.of("qos"),
                  "mqtt qos " + std::to_string(mqtt.qos) + " is not 0, 1 or 2");
        }
        const auto base_problem = topic_problem(mqtt.base_topic);
        base_ok_ = base_problem.empty();
        if (!base_ok_) {
            error(mqtt.marks.of("base_topic"),
                  "base_topic " + in_quotes(mqtt.base_topic) + " " + base_problem);
        } else if (mqtt.base_topic.front() == '$') {
            error(mqtt.marks.of("base_topic"), "base_topic " + in_quotes(mqtt.base_topic) +
                                                   " starts with '$' (reserved by brokers)");
        }
        // Only a written one: the default, eip2mqtt-{gateway.id}, is as good as gateway.id.
        if (mqtt.marks.contains("client_id")) {
            if (const auto problem = plan::text_problem(mqtt.client_id); !problem.empty()) {
                error(mqtt.marks.of("client_id"),
                      "client_id " + in_quotes(mqtt.client_id) + " " + std::string(problem));
            } else if (mqtt.client_id.size() > max_string_bytes) {
                error(mqtt.marks.of("client_id"),
                      "client_id is " + std::to_string(mqtt.client_id.size()) +
                          " bytes long (MQTT allows " + std::to_string(max_string_bytes) + ")");
            }
        }
        if (mqtt.url.empty()) error(mqtt.marks.of("url"), "mqtt url is empty");
        if (mqtt.buffer_max_messages == 0) {
            error(mqtt.marks.of("buffer"), "buffer max_messages must be at least 1");
        }
        if (mqtt.batch_first && !mqtt.batch) {
            error(mqtt.marks.of("batch_first"),
                  "batch_first puts _values first, and needs batch: true to have any");
        }
        if (mqtt.keepalive.count() <= 0) {
            error(mqtt.marks.of("keepalive_s"), "keepalive_s must be at least 1");
        }
        if (mqtt.metrics_interval.count() <= 0) {
            error(mqtt.marks.of("metrics_interval_s"), "metrics_interval_s must be at least 1");
        }
    }

    /// The gateway's own topics fit MQTT's length. A base_topic too long for any of them is
    /// said once, here, and the lengths of exchange and tag topics are not checked then.
    void check_gateway_topics() {
        if (!base_ok_ || !id_ok_) return;
        const auto& base = config_.mqtt.base_topic;
        const auto& id = config_.gateway.id;
        constexpr std::string_view pattern = "{base_topic}/_gateway/{gateway.id}/metrics";
        const std::size_t fixed = base.size() + gateway_level.size() + metrics_suffix.size();
        if (fixed + 1 > plan::max_topic_bytes) {
            error(config_.mqtt.marks.of("base_topic"),
                  "base_topic " + in_quotes(base) + " " + too_long(pattern, fixed + id.size()));
            base_ok_ = false;
        } else if (fixed + id.size() > plan::max_topic_bytes) {
            error(config_.gateway.marks.of("id"),
                  "gateway id " + in_quotes(id) + " " + too_long(pattern, fixed + id.size()));
        }
    }

    void check_exchanges() {
        if (config_.exchanges.empty()) {
            error({config_.file, 1, 1}, "no exchanges configured");
            return;
        }
        std::map<std::string, const ExchangeConfig*> names;
        std::map<std::tuple<Direction, wire::ExchangeKey>, const ExchangeConfig*> keys;
        std::set<const ExchangeConfig*> duplicate_names;
        for (const auto& exchange : config_.exchanges) {
            const auto& spec = exchange.spec;
            if (spec.name.empty()) {
                error(exchange.marks.of("name"), "an exchange has an empty name");
            } else if (const auto problem = plan::text_problem(spec.name); !problem.empty()) {
                error(exchange.marks.of("name"),
                      "exchange name " + in_quotes(spec.name) + " " + std::string(problem));
            } else if (const auto [it, fresh] = names.emplace(spec.name, &exchange); !fresh) {
                error(exchange.marks.of("name"),
                      "duplicate exchange name " + in_quotes(spec.name) + " (first at line " +
                          std::to_string(it->second->marks.of("name").line) + ")");
                duplicate_names.insert(&exchange);
            }
            const auto key = std::make_tuple(spec.direction,
                                             wire::ExchangeKey{spec.producer_id, spec.exchange_id});
            if (const auto [it, fresh] = keys.emplace(key, &exchange); !fresh) {
                error(exchange.marks.of("exchange_id"),
                      std::string(spec.direction == Direction::consume ? "consumed" : "produced") +
                          " exchange " + in_quotes(spec.name) + " has the same producer_id " +
                          wire::to_string(spec.producer_id) + " and exchange_id " +
                          std::to_string(spec.exchange_id) + " as exchange " +
                          in_quotes(it->second->spec.name));
            }
            check_exchange(exchange);
        }
        detail::check_topic_collisions(config_, duplicate_names, out_);
    }

    void check_exchange(const ExchangeConfig& exchange) {
        const auto& spec = exchange.spec;
        const auto& marks = exchange.marks;
        const std::string what = "exchange " + in_quotes(spec.name);
        if (spec.length && (*spec.length == 0 || *spec.length > wire::max_data_size)) {
            error(marks.of("length"), what + " length " + std::to_string(*spec.length) +
                                          " is outside 1.." + std::to_string(wire::max_data_size));
        }
        if (!spec.length && exchange.tags.empty()) {
            error(marks.of("name"), what + " needs a length or at least one tag");
        }
        const auto period = spec.period.count();
        if (period < min_period_ms || period > max_period_ms) {
            error(marks.of("period_ms"),
                  what + " period_ms " + std::to_string(period) + " is outside 2..3600000");
        }
        check_direction(exchange, what);
        check_tags(exchange, check_exchange_topic(exchange, what));
    }

    /// The keys that only one direction may have.
    void check_direction(const ExchangeConfig& exchange, const std::string& what) {
        const auto& spec = exchange.spec;
        const auto& marks = exchange.marks;
        if (spec.direction == Direction::consume) {
            if (!spec.destination.empty()) {
                error(marks.of("destination"),
                      "consumed " + what + " has a destination (only produced exchanges send)");
            }
            if (spec.timeout && spec.timeout->count() < 0) {
                error(marks.of("timeout_ms"), what + " timeout_ms is negative");
            }
        } else {
            if (spec.destination.empty()) {
                error(marks.of("name"), "produced " + what + " has no destination");
            }
            if (spec.timeout) {
                error(marks.of("timeout_ms"),
                      "produced " + what + " has a timeout_ms (consumed exchanges only)");
            }
            if (spec.source) {
                error(marks.of("source"),
                      "produced " + what + " has a source (consumed exchanges only)");
            }
            // A produced datagram carries the gateway's own time.
            for (const auto* key : {"timestamp", "clock_tolerance_ms"}) {
                if (marks.contains(key)) {
                    error(marks.of(key),
                          "produced " + what + " has a " + key + " (consumed exchanges only)");
                }
            }
        }
    }

    /// The exchange's topic; returns the length of {base}/{topic}, or 0 when it is unknown or
    /// already too long (its tags' topics are then not checked for length).
    std::size_t check_exchange_topic(const ExchangeConfig& exchange, const std::string& what) {
        const auto& spec = exchange.spec;
        const auto& marks = exchange.marks;
        const bool topic_is_name = !marks.contains("topic");
        std::size_t topic_bytes = 0;  // of {base}/{topic}; 0: unknown, or too long already
        if (const auto problem = topic_problem(spec.topic); !problem.empty()) {
            // A topic that defaults to a name refused for its text was reported with the name.
            if (!topic_is_name || plan::text_problem(spec.name).empty()) {
                error(marks.of("topic"), what + " topic " + in_quotes(spec.topic) + " " + problem);
            }
        } else {
            std::size_t start = 0;
            while (start <= spec.topic.size()) {
                const auto end = std::min(spec.topic.find('/', start), spec.topic.size());
                const auto level = std::string_view(spec.topic).substr(start, end - start);
                if (level.front() == '_') {
                    error(marks.of("topic"),
                          what + " topic " + in_quotes(spec.topic) +
                              " has a level starting with '_' (reserved for the gateway)");
                    break;
                }
                // Like a tag name: under a topic with a `set` level, an exchange's own topics
                // would be another's write topics, or share their /set/result.
                if (level == "set") {
                    error(marks.of("topic"),
                          what + " topic " + in_quotes(spec.topic) +
                              " has a level 'set', reserved for writes: the gateway takes "
                              "{topic}/set and {topic}/{tag}/set as write requests and answers "
                              "on their /set/result");
                    break;
                }
                start = end + 1;
            }
            if (base_ok_) {
                topic_bytes = config_.mqtt.base_topic.size() + 1 + spec.topic.size();
                if (topic_bytes + result_suffix.size() > plan::max_topic_bytes) {
                    error(topic_is_name ? marks.of("name") : marks.of("topic"),
                          what + " topic " + in_quotes(spec.topic) + " " +
                              too_long("{base_topic}/{topic}/set/result",
                                       topic_bytes + result_suffix.size()));
                    topic_bytes = 0;  // and so are its tags': said once, here
                }
            }
        }
        return topic_bytes;
    }

    /// `topic_bytes`: the length of the exchange's topic, whose tags' topics are checked for
    /// length; 0: they are not.
    void check_tags(const ExchangeConfig& exchange, std::size_t topic_bytes) {
        const auto& spec = exchange.spec;
        const std::size_t limit = spec.length ? *spec.length : wire::max_data_size;
        // Messages are built only for tags in error: a configuration may hold 100,000 tags.
        const auto of_exchange = [&] { return " of exchange " + in_quotes(spec.name); };

        find_repeated_names(exchange);

        for (std::size_t i = 0; i < exchange.tags.size(); ++i) {
            const auto& tag = exchange.tags[i];
            const auto& t = tag.spec;
            const auto& marks = tag.marks;
            const auto what = [&] { return "tag " + in_quotes(t.name) + of_exchange(); };

            if (const auto problem = tag_name_problem(t.name); !problem.empty()) {
                error(marks.of("name"), problem + of_exchange());
            } else {
                if (const int repeated = first_with_name_[i]; repeated >= 0) {
                    const auto& first =
                        exchange.tags[static_cast<std::size_t>(repeated)].marks.of("name");
                    error(marks.of("name"), "duplicate tag name " + in_quotes(t.name) +
                                                of_exchange() + " (first at " + first.file.str() +
                                                ":" + std::to_string(first.line) + ")");
                }
                const std::size_t bytes = topic_bytes + 1 + t.name.size() + result_suffix.size();
                if (topic_bytes > 0 && bytes > plan::max_topic_bytes) {
                    error(marks.of("name"),
                          what() + " " + too_long("{base_topic}/{topic}/{tag}/set/result", bytes));
                }
            }

            const bool is_bit = t.type == TagType::bit;
            if (!is_bit && t.address.bit != 0) {
                error(marks.of("address"),
                      what() + ": address " + plan::to_string(t.address) +
                          " has a bit number but type " + std::string(plan::to_string(t.type)) +
                          " is not bit (use " + std::to_string(t.address.byte) + ".0)");
            }
            const std::size_t size = plan::size_of(t.type);
            const std::size_t end = std::size_t{t.address.byte} + size;
            if (end > limit) {
                error(marks.of("address"),
                      what() + " (" + plan::to_string(t.address) + ", " +
                          std::string(plan::to_string(t.type)) + ") ends at byte " +
                          std::to_string(end) + ", past the exchange " +
                          (spec.length ? "length " : "maximum length ") + std::to_string(limit));
            }

            check_values(exchange, tag);
        }
    }

    /// Fills first_with_name_: for each tag of `exchange`, the index of the first tag with the
    /// same (valid) name, or -1. Sorting views of the names costs less than a hash-map node per
    /// tag (a configuration may hold 100,000 tags).
    void find_repeated_names(const ExchangeConfig& exchange) {
        by_name_.clear();
        for (std::size_t i = 0; i < exchange.tags.size(); ++i) {
            const auto& name = exchange.tags[i].spec.name;
            if (tag_name_problem(name).empty()) by_name_.emplace_back(name, i);
        }
        std::sort(by_name_.begin(), by_name_.end());  // by name, then by position
        first_with_name_.assign(exchange.tags.size(), -1);
        for (std::size_t k = 1; k < by_name_.size(); ++k) {
            if (by_name_[k].first != by_name_[k - 1].first) continue;
            const auto previous = by_name_[k - 1].second;
            first_with_name_[by_name_[k].second] = first_with_name_[previous] >= 0
                                                       ? first_with_name_[previous]
                                                       : static_cast<int>(previous);
        }
    }

    void check_values(const ExchangeConfig& exchange, const TagConfig& tag) {
        const auto& t = tag.spec;
        const auto& marks = tag.marks;
        // Built only for a tag in error: a configuration may hold 100,000 tags.
        const auto what = [&] {
            return "tag " + in_quotes(t.name) + " of exchange " + in_quotes(exchange.spec.name);
        };
        if (t.writable && exchange.spec.direction == Direction::consume) {
            error(marks.of("writable"),
                  what() + " is writable, but only tags of produced exchanges can be written");
        }
        if (t.deadband < 0) error(marks.of("deadband"), what() + " has a negative deadband");
        if (t.refresh.count() < 0)
            error(marks.of("refresh_s"), what() + " has a negative refresh_s");

        const double lo = plan::type_min(t.type);
        const double hi = plan::type_max(t.type);
        const auto type = [&] { return std::string(plan::to_string(t.type)); };
        const auto in_range = [&](std::string_view key, double value) {
            if (value < lo || value > hi) {
                error(marks.of(key), what() + " " + std::string(key) + " " + format_number(value) +
                                         " is outside the range of " + type() + " (" +
                                         format_number(lo) + ".." + format_number(hi) + ")");
                return false;
            }
            return true;
        };
        const auto& min = t.min();
        const auto& max = t.max();
        const bool min_ok = !min || in_range("min", *min);
        const bool max_ok = !max || in_range("max", *max);
        if (min && max && min_ok && max_ok && *min > *max) {
            error(marks.of("max"),
                  what() + " has min " + format_number(*min) + " above max " + format_number(*max));
        }
        if (t.initial()) {
            const double initial = as_double(*t.initial());
            if (in_range("initial", initial)) {
                if (min && initial < *min) {
                    error(marks.of("initial"), what() + " initial " + format_number(initial) +
                                                   " is below min " + format_number(*min));
                } else if (max && initial > *max) {
                    error(marks.of("initial"), what() + " initial " + format_number(initial) +
                                                   " is above max " + format_number(*max));
                }
            }
        }
    }

    const Config& config_;
    Diagnostics out_;
    bool id_ok_ = false;    ///< gateway.id is a valid topic level
    bool base_ok_ = false;  ///< base_topic is a valid topic, short enough for some under it
    std::vector<std::pair<std::string_view, std::size_t>> by_name_;  ///< find_repeated_names
    std::vector<int> first_with_name_;
};

}  // namespace

Diagnostics validate(const Config& config) { return Validator(config).run(); }

std::vector<plan::ExchangePlan> make_plans(const Config& config) {
    std::vector<plan::ExchangePlan> plans;
    plans.reserve(config.exchanges.size());
    for (const auto& exchange : config.exchanges) {
        plan::ExchangeSpec spec = exchange.spec;
        spec.tags.clear();
        spec.tags.reserve(exchange.tags.size());
        for (const auto& tag : exchange.tags) spec.tags.push_back(tag.spec);
        plans.push_back(plan::make_exchange_plan(std::move(spec), config.mqtt.base_topic,
                                                 config.gateway.exchange_defaults));
    }
    return plans;
}

}  // namespace eip2mqtt::core::config
