#pragma once
/// `mqtt.topic_template`: the topic of each tag, as levels of literal text and placeholders:
/// `{base}` (mqtt.base_topic), `{exchange}` (the exchange's topic), `{tag}` (the tag's
/// topic_name, by default its name) and the keys of `location`. A level that expands to nothing
/// is left out, so a tag without an `area` is one level shorter, never given an empty level.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace eip2mqtt::core::plan {

/// Today's topics: {base_topic}/{exchange topic}/{tag name}.
inline constexpr std::string_view default_topic_template = "{base}/{exchange}/{tag}";

/// The placeholders every template may use besides the location keys.
inline constexpr std::string_view base_placeholder = "base";
inline constexpr std::string_view exchange_placeholder = "exchange";
inline constexpr std::string_view tag_placeholder = "tag";

class TopicTemplate {
public:
    /// What a placeholder stands for; an empty view leaves it out.
    using Lookup = std::function<std::string_view(std::string_view placeholder)>;

    /// The template of `text`, or nullopt with `problem` set: an unclosed or empty `{}`, a
    /// brace outside a placeholder, a wildcard, an empty level, or no `{tag}` (every tag of an
    /// exchange would share one topic).
    static std::optional<TopicTemplate> parse(std::string_view text, std::string& problem);

    /// The template every gateway had before templates: default_topic_template.
    static const TopicTemplate& standard();

    /// Each placeholder named, once, in order of appearance.
    const std::vector<std::string>& placeholders() const { return placeholders_; }
    bool is_standard() const { return text_ == default_topic_template; }
    const std::string& text() const { return text_; }

    /// The topic `lookup` fills in, into `out` (replacing its content).
    void expand_into(const Lookup& lookup, std::string& out) const;
    std::string expand(const Lookup& lookup) const;

private:
    struct Part {
        std::string text;
        bool placeholder = false;
    };
    std::string text_;
    std::vector<std::vector<Part>> levels_;
    std::vector<std::string> placeholders_;
};

}  // namespace eip2mqtt::core::plan
