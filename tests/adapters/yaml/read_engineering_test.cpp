// A tag's engineering keys through the loader and the core's checks: scale, type_eu, the
// percent deadband, publish_raw, initial in engineering units, arrays (count) and strings
// (length, trim).

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "tests/adapters/yaml/loading.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

using core::plan::ScaleKind;
using core::plan::ScaleRange;

/// A configuration with one produced exchange of 32 bytes whose tags are `tags` (flow list
/// entries, one per line, each indented as a list item of `tags:`).
std::string with_tags(const std::string& tags, const std::string& exchange_keys = "") {
    return "exchanges:\n"
           "  - name: ex\n"
           "    direction: produce\n"
           "    producer_id: 10.0.0.1\n"
           "    exchange_id: 1\n"
           "    destination: 127.0.0.1\n"
           "    length: 32\n" +
           exchange_keys + "    tags:\n" + tags;
}

const core::plan::TagSpec& only_tag(const Config& config) {
    return config.exchanges.at(0).tags.at(0).spec;
}

TEST(ReadEngineering, TheIssuesExampleLoads) {
    const auto config = good(with_tags(
        "      - { name: level, address: \"0.0\", type: int, unit: \"%\",\n"
        "          scale: { raw: [0, 32000], eu: [0, 100], clamp: true },\n"
        "          deadband: { percent: 0.5 } }\n"
        "      - { name: flow, address: \"2.0\", type: uint, unit: \"m3/h\",\n"
        "          scale: { raw: [0, 65535], eu: [0, 500], sqrt: true } }\n"
        "      - { name: oil_temp, address: \"4.0\", type: dint, unit: \"degC\",\n"
        "          scale: { gain: 0.1, offset: -40 }, writable: true, min: -40, max: 150 }\n"));
    const auto& tags = config.exchanges.at(0).tags;
    const auto& level = tags.at(0).spec;
    ASSERT_TRUE(level.scale());
    EXPECT_EQ(level.scale()->kind, ScaleKind::linear);
    EXPECT_EQ(level.scale()->raw, (ScaleRange{0, 32000}));
    EXPECT_EQ(level.scale()->eu, (ScaleRange{0, 100}));
    EXPECT_TRUE(level.scale()->clamp);
    EXPECT_EQ(level.deadband_percent(), 0.5);
    EXPECT_DOUBLE_EQ(level.deadband, 0.5);  // 0.5 % of 100
    EXPECT_EQ(tags.at(1).spec.scale()->kind, ScaleKind::square_root);
    const auto& oil = tags.at(2).spec;
    EXPECT_EQ(oil.scale()->kind, ScaleKind::gain_offset);
    EXPECT_EQ(oil.scale()->gain, 0.1);
    EXPECT_EQ(oil.scale()->offset, -40);
    EXPECT_EQ(oil.min(), -40);  // engineering values: outside no scale's range
    EXPECT_EQ(tags.at(2).marks.of("scale.gain").line, 15);
}

TEST(ReadEngineering, APercentDeadbandTakesMinAndMaxWithoutAScale) {
    const auto config =
        good(with_tags("      - { name: t, address: 0.0, type: real, min: -50, max: 150, "
                       "deadband: { percent: 1 } }\n"));
    EXPECT_DOUBLE_EQ(only_tag(config).deadband, 2.0);
}

TEST(ReadEngineering, TypeEuAndPublishRaw) {
    const auto config = good(with_tags(
        "      - { name: a, address: 0.0, type: int, scale: { gain: 0.5 }, type_eu: dint }\n"
        "      - { name: b, address: 2.0, type: int, publish_raw: false }\n"
        "      - { name: c, address: 4.0, type: int }\n",
        "    publish_raw: true\n"));
    const auto& tags = config.exchanges.at(0).tags;
    EXPECT_EQ(tags.at(0).spec.scale()->eu_type, TagType::dint);
    EXPECT_TRUE(tags.at(0).spec.publish_raw());   // the exchange's
    EXPECT_FALSE(tags.at(1).spec.publish_raw());  // its own
    EXPECT_TRUE(tags.at(2).spec.publish_raw());
}

TEST(ReadEngineering, InitialIsInEngineeringUnitsAndKeptRaw) {
    const auto config = good(
        with_tags("      - { name: t, address: 0.0, type: dint, writable: true, initial: 25.2,\n"
                  "          scale: { gain: 0.1, offset: -40 } }\n"));
    EXPECT_EQ(only_tag(config).initial(), core::plan::Value{std::int64_t{652}});
}

/// The one diagnostic of `text`, which must fail to load with exactly one.
core::config::Diagnostic one_error(const std::string& text) {
    const auto d = bad(text);
    EXPECT_EQ(d.size(), 1u) << dump(d);
    return d.empty() ? core::config::Diagnostic{} : d.front();
}

void expect_error(const std::string& tags, int line, int column, const std::string& words) {
    const auto d = one_error(with_tags(tags));
    EXPECT_EQ(d.mark.line, line) << d.message;
    EXPECT_EQ(d.mark.column, column) << d.message;
    EXPECT_NE(d.message.find(words), std::string::npos) << d.message;
}

TEST(ReadEngineering, BadScalesAreRefusedAtTheirLineAndColumn) {
    // Lines count from 1; the tags start on line 9.
    expect_error(
        "      - { name: t, address: 0.0, type: int, scale: { raw: [5, 5], eu: [0, 1] } }\n", 9, 54,
        "raw ends are equal");
    expect_error(
        "      - { name: t, address: 0.0, type: int, scale: { raw: [0, 5], eu: [2, 2] } }\n", 9, 67,
        "eu ends are equal");
    expect_error(
        "      - { name: t, address: 0.0, type: int,\n"
        "          scale: { raw: [-100, 5], eu: [0, 1], sqrt: true } }\n",
        10, 20, "negative count has no root");
    expect_error("      - { name: t, address: 0.0, type: bit, scale: { gain: 2 } }\n", 9, 45,
                 "a bit has no scale");
    expect_error("      - { name: t, address: 0.0, type: int, scale: { gain: 0 } }\n", 9, 54,
                 "other than 0");
    expect_error("      - { name: t, address: 0.0, type: int, scale: { raw: [0, 5] } }\n", 9, 45,
                 "lacks 'eu'");
    expect_error(
        "      - { name: t, address: 0.0, type: int, scale: { raw: [0, 5], eu: [0, 1], gain: 2 } "
        "}\n",
        9, 45, "not both");
    expect_error("      - { name: t, address: 0.0, type: int, scale: { gain: 2, clamp: true } }\n",
                 9, 45, "'clamp' needs");
    expect_error("      - { name: t, address: 0.0, type: int, scale: { raw: 5, eu: [0, 1] } }\n", 9,
                 54, "expected two numbers");
    expect_error("      - { name: t, address: 0.0, type: int, scale: { rwa: [0, 1] } }\n", 9, 54,
                 "did you mean 'raw'");
}

TEST(ReadEngineering, BadDeadbandsTypeEuAndLimitsAreRefused) {
    expect_error("      - { name: t, address: 0.0, type: int, deadband: { percent: 2 } }\n", 9, 45,
                 "no span");
    expect_error(
        "      - { name: t, address: 0.0, type: int, scale: { gain: 2 }, deadband: { percent: 2 } "
        "}\n",
        9, 65, "no span");
    expect_error("      - { name: t, address: 0.0, type: int, type_eu: dint }\n", 9, 45,
                 "add 'scale'");
    expect_error("      - { name: t, address: 0.0, type: int, scale: { gain: 2 }, type_eu: bit }\n",
                 9, 65, "'type_eu' 'bit'");
    expect_error(
        "      - { name: t, address: 0.0, type: int, writable: true, max: 101,\n"
        "          scale: { raw: [0, 32000], eu: [0, 100] } }\n",
        9, 61, "outside the engineering range 0..100");
    expect_error(
        "      - { name: t, address: 0.0, type: int, writable: true, initial: 200,\n"
        "          scale: { raw: [0, 32000], eu: [0, 100] } }\n",
        9, 61, "raw form is outside the range of int");
    expect_error(
        "      - { name: t, address: 0.0, type: word, writable: true, initial: -1,\n"
        "          scale: { raw: [0, 32000], eu: [0, 100], sqrt: true } }\n",
        9, 62, "below the square root's zero");
}

TEST(ReadEngineering, ALargeValueBeyondTheTypeStaysAnEngineeringValue) {
    // max 3000 is no int16 limit here: it is of the engineering range.
    const auto config = good(
        with_tags("      - { name: t, address: 0.0, type: int, writable: true, min: 0, max: 3000,\n"
                  "          scale: { raw: [0, 30000], eu: [0, 3000] } }\n"));
    EXPECT_EQ(only_tag(config).max(), 3000);
    const auto large =
        good(with_tags("      - { name: t, address: 0.0, type: byte, writable: true, max: 100000,\n"
                       "          scale: { gain: 1000 } }\n"));
    EXPECT_EQ(only_tag(large).max(), 100000);
}

TEST(ReadArraysAndStrings, TheIssuesExampleLoads) {
    const auto config = good(with_tags(
        "      - { name: bearing_temps, address: \"8.0\", type: real, count: 4, unit: \"degC\",\n"
        "          writable: true, initial: [20, 21, 22, 23.5] }\n"
        "      - { name: batch_id, address: \"24.0\", type: string, length: 8, writable: true,\n"
        "          initial: \"B-\u00e9\" }\n"
        "      - { name: flags, address: \"0.6\", type: bit, count: 4, trim: true }\n",
        ""));
    const auto& tags = config.exchanges.at(0).tags;
    const auto& temps = tags.at(0).spec;
    EXPECT_EQ(temps.count, 4);
    EXPECT_TRUE(temps.is_array());
    EXPECT_EQ(core::plan::to_json(*temps.initial()), "[20.0,21.0,22.0,23.5]");
    const auto& batch = tags.at(1).spec;
    EXPECT_EQ(batch.type, core::plan::TagType::string);
    EXPECT_EQ(batch.count, 8);
    EXPECT_FALSE(batch.is_array());
    EXPECT_EQ(core::plan::to_json(*batch.initial()), "\"B-\xC3\xA9\"");
    EXPECT_EQ(tags.at(2).spec.count, 4);
}

TEST(ReadArraysAndStrings, OneInitialValueFillsEveryElement) {
    const auto config = good(with_tags(
        "      - { name: sp, address: 0.0, type: int, count: 3, writable: true, initial: 7 }\n"));
    EXPECT_EQ(core::plan::to_json(*only_tag(config).initial()), "[7,7,7]");
}

TEST(ReadArraysAndStrings, KeepingThePaddingIsTheTagsChoice) {
    const auto config = good(
        with_tags("      - { name: s, address: 0.0, type: string, length: 4, trim: false }\n"));
    EXPECT_FALSE(only_tag(config).trim());
}

TEST(ReadArraysAndStrings, BadShapesAreRefusedAtTheirLineAndColumn) {
    expect_error("      - { name: t, address: 30.0, type: int, count: 2 }\n", 9, 20,
                 "ends at byte 34, past the exchange length 32");
    expect_error("      - { name: t, address: 0.0, type: int, count: 1 }\n", 9, 45,
                 "an array has 2 elements or more");
    expect_error("      - { name: t, address: 0.0, type: lreal, count: 176 }\n", 9, 47,
                 "at most 175 of lreal fit an exchange");
    expect_error("      - { name: t, address: 0.0, type: bit, count: 11201 }\n", 9, 45,
                 "at most 11200 of bit fit an exchange");
    expect_error("      - { name: t, address: 0.0, type: string, length: 0 }\n", 9, 48,
                 "a string of no bytes");
    expect_error("      - { name: t, address: 0.0, type: string }\n", 9, 9, "a string of no bytes");
    expect_error("      - { name: t, address: 0.0, type: string, count: 4 }\n", 9, 48,
                 "takes length, not count");
    expect_error("      - { name: t, address: 0.0, type: int, length: 4 }\n", 9, 45,
                 "only a string has a length");
    expect_error("      - { name: t, address: 0.0, type: string, length: 4, scale: { gain: 2 } }\n",
                 9, 59, "a string has no scale");
    expect_error("      - { name: t, address: 0.0, type: string, length: 4, max: 3 }\n", 9, 59,
                 "a string: it has no max");
}

TEST(ReadArraysAndStrings, BadInitialValuesAreRefused) {
    expect_error(
        "      - { name: t, address: 0.0, type: int, count: 3, writable: true, initial: [1, 2] }\n",
        9, 71, "'initial' has 2 values for an array of 3");
    expect_error(
        "      - { name: t, address: 0.0, type: string, length: 2, writable: true, initial: abc "
        "}\n",
        9, 75, "longer than the string's length 2");
    expect_error(
        "      - { name: t, address: 0.0, type: string, length: 4, writable: true,\n"
        "          initial: \"5 \u20ac\" }\n",
        10, 11, "Latin-1");
    expect_error(
        "      - { name: t, address: 0.0, type: byte, count: 2, writable: true, initial: [1, 300] "
        "}\n",
        9, 72, "initial 300 is outside the range of byte");
}

TEST(ReadArraysAndStrings, TheReadmesExampleLoadsAsItIsPrinted) {
    // README.md's Configuration part: its `tags:` block, as a produced exchange's.
    std::ifstream readme(std::string(EIP2MQTT_SOURCE_DIR) + "/README.md");
    const std::string text((std::istreambuf_iterator<char>(readme)), {});
    const auto part = text.find("## Configuration");
    ASSERT_NE(part, std::string::npos);
    const auto first = text.find("```yaml\ntags:\n", part);
    ASSERT_NE(first, std::string::npos);
    const auto from = first + std::string("```yaml\ntags:\n").size();
    std::istringstream block(text.substr(from, text.find("```", from) - from));
    std::string tags;
    for (std::string line; std::getline(block, line);) tags += "    " + line + "\n";
    const auto config = good(std::string("exchanges:\n") +
                             "  - name: ex\n"
                             "    direction: produce\n"
                             "    producer_id: 10.0.0.1\n"
                             "    exchange_id: 1\n"
                             "    destination: 127.0.0.1\n"
                             "    tags:\n" +
                             tags);
    const auto& loaded = config.exchanges.at(0).tags;
    ASSERT_EQ(loaded.size(), 5u);
    EXPECT_TRUE(loaded.at(0).spec.scale());
    EXPECT_EQ(loaded.at(3).spec.count, 4);
    EXPECT_EQ(loaded.at(4).spec.type, core::plan::TagType::string);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
