// mqtt.topic_template: how a template reads, and the topics it makes (docs/configuration.md,
// "Topics and payloads").

#include "eip2mqtt/core/plan/topic_template.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::plan {
namespace EIP2MQTT_THIS_FILE {

TopicTemplate parsed(std::string_view text) {
    std::string problem;
    auto out = TopicTemplate::parse(text, problem);
    EXPECT_TRUE(out.has_value()) << text << ": " << problem;
    return out ? *out : TopicTemplate::standard();
}

std::string problem_of(std::string_view text) {
    std::string problem;
    EXPECT_FALSE(TopicTemplate::parse(text, problem).has_value()) << text;
    return problem;
}

std::string expand(const TopicTemplate& t, const std::map<std::string, std::string>& values) {
    return t.expand([&](std::string_view name) -> std::string_view {
        const auto it = values.find(std::string(name));
        return it == values.end() ? std::string_view() : std::string_view(it->second);
    });
}

TEST(TopicTemplate, TheDefaultIsTodaysLayout) {
    const auto& t = TopicTemplate::standard();
    EXPECT_TRUE(t.is_standard());
    EXPECT_EQ(t.placeholders(), (std::vector<std::string>{"base", "exchange", "tag"}));
    EXPECT_EQ(expand(t, {{"base", "acme"}, {"exchange", "t1/in"}, {"tag", "SPEED"}}),
              "acme/t1/in/SPEED");
}

TEST(TopicTemplate, PlaceholdersAreNamedOnceInOrder) {
    const auto t = parsed("{enterprise}/{site}/line-{line}/{asset}/{tag}/{site}");
    EXPECT_FALSE(t.is_standard());
    EXPECT_EQ(t.placeholders(),
              (std::vector<std::string>{"enterprise", "site", "line", "asset", "tag"}));
}

TEST(TopicTemplate, ALevelThatExpandsToNothingIsLeftOut) {
    const auto t = parsed("{enterprise}/{site}/{area}/{asset}/{tag}");
    EXPECT_EQ(expand(t, {{"enterprise", "acme"}, {"site", "plant1"}, {"tag", "SPEED"}}),
              "acme/plant1/SPEED");
    EXPECT_EQ(expand(t, {{"tag", "SPEED"}}), "SPEED");
}

TEST(TopicTemplate, LiteralTextKeepsItsLevelAndValuesMayHoldLevels) {
    const auto t = parsed("uns/line-{line}/{asset}/{tag}");
    EXPECT_EQ(expand(t, {{"asset", "t1/lube-pump"}, {"tag", "pressure"}}),
              "uns/line-/t1/lube-pump/pressure");
    EXPECT_EQ(expand(t, {{"line", "4"}, {"asset", "t1"}, {"tag", "SPEED"}}), "uns/line-4/t1/SPEED");
}

TEST(TopicTemplate, WhatCannotBeATemplateIsRefusedWithTheReason) {
    EXPECT_EQ(problem_of(""), "is empty");
    EXPECT_EQ(problem_of("a/+/{tag}"), "contains a wildcard ('+' or '#')");
    EXPECT_EQ(problem_of("a/#"), "contains a wildcard ('+' or '#')");
    EXPECT_EQ(problem_of("/a/{tag}"), "has an empty level (leading, trailing or double '/')");
    EXPECT_EQ(problem_of("a//{tag}"), "has an empty level (leading, trailing or double '/')");
    EXPECT_EQ(problem_of("a/{tag}/"), "has an empty level (leading, trailing or double '/')");
    EXPECT_EQ(problem_of("a/{tag"), "has a '{' without its '}'");
    EXPECT_EQ(problem_of("a}/{tag}"), "has a '}' without its '{'");
    EXPECT_EQ(problem_of("a/{}/{tag}"), "has an empty placeholder '{}'");
    EXPECT_EQ(problem_of("a/{x{y}/{tag}"), "has a '{' inside a placeholder");
    EXPECT_EQ(problem_of("{base}/{exchange}"),
              "has no {tag}: every tag of an exchange would have the same topic");
    EXPECT_FALSE(problem_of(std::string("a/\x01/{tag}")).empty());
}

ExchangeSpec spec_with(std::vector<TagSpec> tags) {
    ExchangeSpec spec;
    spec.name = "turbine1";
    spec.topic = "t1";
    spec.length = 16;
    spec.location.levels = {{"area", "turbine-hall"}, {"asset", "t1"}};
    spec.tags = std::move(tags);
    return spec;
}

TagSpec tag_named(std::string name, std::uint16_t byte) {
    TagSpec t;
    t.name = std::move(name);
    t.address = {byte, 0};
    t.type = TagType::real;
    return t;
}

TEST(TagTopics, TheDefaultLayoutKeepsNoTopicPerTag) {
    const auto plan = make_exchange_plan(spec_with({tag_named("SPEED", 0)}), "acme");
    EXPECT_TRUE(plan.tag_topics.empty());
    EXPECT_EQ(plan.tag_topic(plan.tags[0]), "acme/t1/SPEED");
}

TEST(TagTopics, TheNearerLocationWinsAndATagsTopicOverridesTheTemplate) {
    auto lube = tag_named("LUBE_P", 4);
    lube.mutable_extras().location.levels = {{"asset", "t1/lube-pump"}};
    lube.mutable_extras().topic_name = "pressure";
    auto fixed = tag_named("FIXED", 8);
    fixed.mutable_extras().topic = "elsewhere/fixed";
    auto cleared = tag_named("NO_AREA", 12);
    cleared.mutable_extras().location.levels = {{"area", ""}};
    const auto tmpl = parsed("{enterprise}/{site}/{area}/{asset}/{tag}");
    const Location gateway{{{"enterprise", "acme"}, {"site", "plant1"}, {"area", "yard"}}};
    const auto plan = make_exchange_plan(spec_with({tag_named("SPEED", 0), lube, fixed, cleared}),
                                         "base", {}, {&tmpl, &gateway});
    EXPECT_EQ(plan.tag_topics,
              (std::vector<std::string>{"acme/plant1/turbine-hall/t1/SPEED",
                                        "acme/plant1/turbine-hall/t1/lube-pump/pressure",
                                        "elsewhere/fixed", "acme/plant1/t1/NO_AREA"}));
    EXPECT_EQ(plan.tag_topic(plan.tags[1]), "acme/plant1/turbine-hall/t1/lube-pump/pressure");
    // The exchange's own topics stay where they were: its status beside its tags' exchange.
    EXPECT_EQ(plan.status_topic, "base/t1/_status");
    EXPECT_EQ(plan.set_topic, "base/t1/set");
}

TEST(TagTopics, OneTagOfItsOwnListsEveryTagsTopic) {
    auto renamed = tag_named("B", 4);
    renamed.mutable_extras().topic_name = "bee";
    const auto plan =
        make_exchange_plan(spec_with({tag_named("A", 0), renamed, tag_named("C", 8)}), "acme");
    EXPECT_EQ(plan.tag_topics, (std::vector<std::string>{"acme/t1/A", "acme/t1/bee", "acme/t1/C"}));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::plan
