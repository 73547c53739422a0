#include "core/config/detail/topic_layout_check.hpp"

#include <algorithm>
#include <set>
#include <string>

#include "core/config/detail/config_names.hpp"
#include "core/config/detail/validator.hpp"
#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::core::config::detail {
namespace {

bool is_own_placeholder(std::string_view name) {
    return name == plan::base_placeholder || name == plan::exchange_placeholder ||
           name == plan::tag_placeholder;
}

std::string location_key_problem(std::string_view key) {
    if (key.empty()) return "is empty";
    if (key.find_first_of("/+#{}") != std::string_view::npos) {
        return "contains '/', '+', '#', '{' or '}'";
    }
    if (is_own_placeholder(key)) return "is a placeholder of the gateway's own";
    return std::string(plan::text_problem(key));
}

std::string location_value_problem(std::string_view value) {
    // Empty says "no such level here", whatever a farther location says.
    return value.empty() ? std::string() : topic_problem(value);
}

class LayoutCheck {
public:
    LayoutCheck(const Config& config, Diagnostics& out) : config_(config), out_(out) {}

    void run() {
        const bool gateway_ok =
            check_location(config_.gateway.location, config_.gateway.marks, "gateway");
        std::set<const void*> broken;  // exchanges and tags whose location is reported
        for (const auto& exchange : config_.exchanges) {
            const auto what = "exchange " + in_quotes(exchange.spec.name);
            if (!check_location(exchange.spec.location, exchange.marks, what)) {
                broken.insert(&exchange);
            }
            for (const auto& tag : exchange.tags) {
                if (tag.spec.location().empty()) continue;
                if (!check_location(tag.spec.location(), tag.marks,
                                    "tag " + in_quotes(tag.spec.name) + " of " + what)) {
                    broken.insert(&tag);
                }
            }
        }
        const auto tmpl = topic_template_of(config_);
        const auto& at = config_.mqtt.marks.of("topic_template");
        if (!tmpl) {
            std::string problem;
            plan::TopicTemplate::parse(config_.mqtt.topic_template, problem);
            out_.push_back(
                {at, "topic_template " + in_quotes(config_.mqtt.topic_template) + " " + problem});
        } else {
            for (const auto& name : tmpl->placeholders()) {
                if (is_own_placeholder(name) || keys_.contains(name)) continue;
                out_.push_back({at, "topic_template's placeholder {" + name +
                                        "} is a key of no location (of the gateway, an "
                                        "exchange or a tag)"});
            }
        }
        // A topic made of a location already refused is not reported again.
        const bool expand = tmpl && gateway_ok;
        for (const auto& exchange : config_.exchanges) {
            for (const auto& tag : exchange.tags) {
                const bool ok = expand && !broken.contains(&exchange) && !broken.contains(&tag);
                check_tag(exchange, tag, ok ? &*tmpl : nullptr);
            }
        }
    }

private:
    /// False when a key or a value of `location` was refused.
    bool check_location(const plan::Location& location, const Marks& marks,
                        const std::string& owner) {
        const auto& at = marks.of("location");
        const auto before = out_.size();
        for (const auto& [key, value] : location.levels) {
            keys_.insert(key);
            if (auto problem = location_key_problem(key); !problem.empty()) {
                out_.push_back({at, owner + ": location key " + in_quotes(key) + " " + problem});
            } else if (auto bad = location_value_problem(value); !bad.empty()) {
                out_.push_back(
                    {at, owner + ": location " + key + " " + in_quotes(value) + " " + bad});
            }
        }
        return out_.size() == before;
    }

    /// `tmpl` null: the tag's own keys alone are checked, not the topic they make.
    void check_tag(const ExchangeConfig& exchange, const TagConfig& tag,
                   const plan::TopicTemplate* tmpl);

    const Config& config_;
    Diagnostics& out_;
    std::set<std::string, std::less<>> keys_;  ///< of every location written
};

void LayoutCheck::check_tag(const ExchangeConfig& exchange, const TagConfig& tag,
                            const plan::TopicTemplate* tmpl) {
    const auto& spec = tag.spec;
    const auto what = [&] {
        return "tag " + in_quotes(spec.name) + " of exchange " + in_quotes(exchange.spec.name);
    };
    if (tag.marks.contains("topic_name")) {
        if (auto problem = tag_name_problem(spec.topic_name()); !problem.empty()) {
            // The rules of a name: it is the tag's level, as its name would be.
            out_.push_back({tag.marks.of("topic_name"), what() + ": topic_name: " + problem});
            return;
        }
    }
    if (tag.marks.contains("topic") && spec.topic().empty()) {
        out_.push_back({tag.marks.of("topic"), what() + ": topic is empty"});
        return;
    }
    const bool own =
        !spec.topic().empty() || !spec.topic_name().empty() || !spec.location().empty();
    if (!tmpl || (tmpl->is_standard() && !own)) return;
    const plan::TopicLayout layout{tmpl, &config_.gateway.location};
    const auto topic = plan::expand_tag_topic(layout, config_.mqtt.base_topic, exchange.spec, spec);
    const auto& at = tag.marks.contains("topic") ? tag.marks.of("topic") : tag.marks.of("name");
    const auto says = [&](const std::string& problem) {
        out_.push_back({at, what() + " gets topic " + in_quotes(topic) + ", which " + problem});
    };
    if (auto problem = topic_problem(topic); !problem.empty()) return says(problem);
    if (topic.front() == '$') return says("starts with '$' (reserved by brokers)");
    const auto& base = config_.mqtt.base_topic;
    const bool under_base =
        topic.starts_with(base) && topic.size() > base.size() && topic[base.size()] == '/';
    if (const auto level = reserved_level(topic, under_base ? base.size() + 1 : 0);
        !level.empty()) {
        return says("has a level " + in_quotes(level) +
                    ", kept for the gateway's own topics ('set' and levels starting with '_')");
    }
    if (const auto bytes = topic.size() + result_suffix.size(); bytes > plan::max_topic_bytes) {
        says(too_long("{tag topic}/set/result", bytes));
    }
}

}  // namespace

std::optional<plan::TopicTemplate> topic_template_of(const Config& config) {
    std::string problem;
    return plan::TopicTemplate::parse(config.mqtt.topic_template, problem);
}

bool laid_out(const Config& config) {
    if (config.mqtt.topic_template != plan::default_topic_template) return true;
    return std::any_of(config.exchanges.begin(), config.exchanges.end(), [](const auto& e) {
        return std::any_of(e.tags.begin(), e.tags.end(), [](const TagConfig& t) {
            return !t.spec.topic().empty() || !t.spec.topic_name().empty();
        });
    });
}

void check_topic_layout(const Config& config, Diagnostics& out) { LayoutCheck(config, out).run(); }

}  // namespace eip2mqtt::core::config::detail
