// The checks of each tag: its name and topic, its address against its type and the exchange's
// length, and its values against its type's range.

#include "core/config/detail/tag_checks.hpp"

#include <algorithm>
#include <variant>

#include "core/config/detail/config_names.hpp"
#include "core/config/detail/engineering_checks.hpp"
#include "core/config/detail/validator.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/scaling.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"

namespace eip2mqtt::core::config::detail {
namespace {

using plan::Direction;
using plan::TagType;

double as_double(const plan::Value& value) { return plan::to_double(value); }

}  // namespace

void TagChecks::run(const ExchangeConfig& exchange, std::size_t topic_bytes, Diagnostics& out) {
    out_ = &out;
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
                error(marks.of("name"), "duplicate tag name " + in_quotes(t.name) + of_exchange() +
                                            " (first at " + first.file.str() + ":" +
                                            std::to_string(first.line) + ")");
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
        const std::size_t end = std::size_t{t.address.byte} + plan::tag_size(t);
        // An array too long for any exchange is reported by its count.
        if (end > limit && plan::tag_size(t) <= wire::max_data_size) {
            error(marks.of("address"),
                  what() + " (" + plan::to_string(t.address) + ", " +
                      std::string(plan::to_string(t.type)) + ") ends at byte " +
                      std::to_string(end) + ", past the exchange " +
                      (spec.length ? "length " : "maximum length ") + std::to_string(limit));
        }

        check_values(exchange, tag);
    }
}

void TagChecks::find_repeated_names(const ExchangeConfig& exchange) {
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

void TagChecks::check_values(const ExchangeConfig& exchange, const TagConfig& tag) {
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
    if (t.refresh.count() < 0) error(marks.of("refresh_s"), what() + " has a negative refresh_s");

    check_engineering(tag, what, *out_);
    if (t.type == TagType::string) return;  // no range: its checks are the engineering ones
    check_limits(tag, what);
}

void TagChecks::check_limits(const TagConfig& tag, const std::function<std::string()>& what) {
    const auto& t = tag.spec;
    const auto& marks = tag.marks;
    const double lo = plan::type_min(t.type);
    const double hi = plan::type_max(t.type);
    const auto type = [&] { return std::string(plan::to_string(t.type)); };
    const auto& scale = t.scale();
    const auto in_range = [&](std::string_view key, double value) {
        // A scaled tag's limits are engineering values; its initial is kept raw.
        if (scale && key != "initial") {
            const auto outside = outside_eu_range(*scale, value);
            if (!outside.empty()) {
                error(marks.of(key),
                      what() + " " + std::string(key) + " " + number_text(value) + outside);
            }
            return outside.empty();
        }
        if (value < lo || value > hi) {
            error(marks.of(key), what() + " " + std::string(key) + " " + number_text(value) +
                                     " is outside the range of " + type() + " (" + number_text(lo) +
                                     ".." + number_text(hi) + ")");
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
              what() + " has min " + number_text(*min) + " above max " + number_text(*max));
    }
    // An array's initial value is checked element by element; a string's by its reader.
    const auto check_initial = [&](const plan::Value& value) {
        const double raw = as_double(value);
        const double initial =
            scale ? plan::to_double(plan::to_engineering(value, *scale).value) : raw;
        if (in_range("initial", raw)) {
            if (min && initial < *min) {
                error(marks.of("initial"), what() + " initial " + number_text(initial) +
                                               " is below min " + number_text(*min));
            } else if (max && initial > *max) {
                error(marks.of("initial"), what() + " initial " + number_text(initial) +
                                               " is above max " + number_text(*max));
            }
        }
    };
    if (!t.initial() || std::holds_alternative<plan::Text>(*t.initial())) return;
    if (const auto* items = plan::list_items(*t.initial())) {
        for (const auto& item : *items) check_initial(item);
    } else {
        check_initial(*t.initial());
    }
}

}  // namespace eip2mqtt::core::config::detail
