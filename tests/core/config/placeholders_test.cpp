// The placeholders import-points marks, as check finds them in the file's text.

#include "eip2mqtt/core/config/placeholders.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

TEST(Placeholders, EachMarkedLineWithItsKeyAndColumn) {
    const auto found = find_placeholders(
        "exchanges:\n"
        "  - name: a\n"
        "    producer_id: 0.0.0.0   # PLACEHOLDER: the producer's id\n"
        "    length: 8\n"
        "  - period_ms: 100 # PLACEHOLDER\n",
        "x.yaml");
    ASSERT_EQ(found.size(), 2u);
    EXPECT_EQ(found[0].key, "producer_id");
    EXPECT_EQ(found[0].mark.file, "x.yaml");
    EXPECT_EQ(found[0].mark.line, 3);
    EXPECT_EQ(found[0].mark.column, 5);
    EXPECT_EQ(found[1].key, "period_ms");
    EXPECT_EQ(found[1].mark.line, 5);
    EXPECT_EQ(found[1].mark.column, 5);
}

TEST(Placeholders, TheMarkerInAQuotedValueOrWithoutItsCommentIsNone) {
    EXPECT_TRUE(find_placeholders("    topic: \"a # PLACEHOLDER b\"\n"
                                  "    description: x#PLACEHOLDER\n"
                                  "    length: 8 # reviewed\n",
                                  "x.yaml")
                    .empty());
}

TEST(Placeholders, ACommentLineNamingTheMarkerIsNone) {
    EXPECT_TRUE(find_placeholders("# Review every line marked # PLACEHOLDER: ...\n"
                                  "  # PLACEHOLDER\n",
                                  "x.yaml")
                    .empty());
}

TEST(Placeholders, AReviewedFileHasNone) {
    EXPECT_TRUE(find_placeholders("", "x.yaml").empty());
    EXPECT_TRUE(find_placeholders("gateway:\n  id: gw\n", "x.yaml").empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
