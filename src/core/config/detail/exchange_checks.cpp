// The checks of each exchange: its name and key, its keys by direction, and its topic.

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include "core/config/detail/config_names.hpp"
#include "core/config/detail/topic_collisions.hpp"
#include "core/config/detail/validator.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::config::detail {

using plan::Direction;

void Validator::check_exchanges() {
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
        const auto key =
            std::make_tuple(spec.direction, wire::ExchangeKey{spec.producer_id, spec.exchange_id});
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

void Validator::check_exchange(const ExchangeConfig& exchange) {
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
    tags_.run(exchange, check_exchange_topic(exchange, what), out_);
}

void Validator::check_direction(const ExchangeConfig& exchange, const std::string& what) {
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

std::size_t Validator::check_exchange_topic(const ExchangeConfig& exchange,
                                            const std::string& what) {
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
        // Like a tag name: under a topic with a `set` level, an exchange's own topics would be
        // another's write topics, or share their /set/result.
        if (const auto level = reserved_level(spec.topic); level == "set") {
            error(marks.of("topic"),
                  what + " topic " + in_quotes(spec.topic) +
                      " has a level 'set', reserved for writes: the gateway takes "
                      "{topic}/set and {topic}/{tag}/set as write requests and answers "
                      "on their /set/result");
        } else if (!level.empty()) {
            error(marks.of("topic"),
                  what + " topic " + in_quotes(spec.topic) +
                      " has a level starting with '_' (reserved for the gateway)");
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

}  // namespace eip2mqtt::core::config::detail
