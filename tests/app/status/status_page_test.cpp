// The status page's resources: the page, its script and its style, each with its type, the
// page loading nothing but the other two (the listener's policy allows its own origin alone).

#include "eip2mqtt/app/status/status_page.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::app::status {
namespace EIP2MQTT_THIS_FILE {

TEST(StatusPage, ServesThePageItsScriptAndItsStyleAndNothingElse) {
    const auto* html = page_resource("/");
    ASSERT_NE(html, nullptr);
    EXPECT_EQ(html->content_type, "text/html; charset=utf-8");
    EXPECT_NE(html->text.find(R"(<script src="/status.js" defer>)"), std::string::npos);
    EXPECT_NE(html->text.find(R"(<link rel="stylesheet" href="/status.css">)"), std::string::npos);
    // Nothing from another origin, and nothing inline the policy would refuse.
    EXPECT_EQ(html->text.find("http://"), std::string::npos);
    EXPECT_EQ(html->text.find("https://"), std::string::npos);
    EXPECT_EQ(html->text.find("<script>"), std::string::npos);
    EXPECT_EQ(html->text.find("style="), std::string::npos);
    ASSERT_NE(page_resource("/status.js"), nullptr);
    EXPECT_EQ(page_resource("/status.js")->content_type, "text/javascript; charset=utf-8");
    EXPECT_NE(page_resource("/status.js")->text.find(R"(new EventSource("/api/events")"),
              std::string::npos);
    // The script writes text, never markup.
    EXPECT_EQ(page_resource("/status.js")->text.find("innerHTML"), std::string::npos);
    ASSERT_NE(page_resource("/status.css"), nullptr);
    EXPECT_EQ(page_resource("/status.css")->content_type, "text/css; charset=utf-8");
    ASSERT_NE(page_resource("/favicon.svg"), nullptr);
    EXPECT_EQ(page_resource("/favicon.svg")->content_type, "image/svg+xml");
    EXPECT_NE(html->text.find(R"(<link rel="icon" href="/favicon.svg")"), std::string::npos);
    EXPECT_EQ(page_resource("/index.html"), nullptr);
    EXPECT_EQ(page_resource("/api/status"), nullptr);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::status
