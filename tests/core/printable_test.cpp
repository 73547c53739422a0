#include "eip2mqtt/core/printable.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::core {
namespace EIP2MQTT_THIS_FILE {

TEST(Printable, ControlBytesAreEscapedAndLongTextIsCut) {
    EXPECT_EQ(printable("plain/topic"), "plain/topic");
    EXPECT_EQ(printable("a\nb\x01\x7f"), "a\\x0ab\\x01\\x7f");
    EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
    EXPECT_EQ(printable(std::string(300, 'x'), 4), "xxxx...");
    EXPECT_EQ(printable("PRESSÃO"), "PRESSÃO");
}

TEST(Printable, TextANodeToldKeepsOnlyPrintableAscii) {
    // An escape sequence, a C1 CSI, a YAML line break (U+2028 in UTF-8) and a newline.
    const std::string told =
        std::string("\x1b[2Jnode\x9b") + "31m\xe2\x80\xa8" + "eip:\n  commands: {}";
    const auto shown = printable_ascii(told);
    EXPECT_EQ(shown, "\\x1b[2Jnode\\x9b31m\\xe2\\x80\\xa8eip:\\x0a  commands: {}");
    for (const char c : shown) {
        EXPECT_TRUE(c >= 0x20 && c < 0x7F) << static_cast<int>(c);
    }
    EXPECT_EQ(printable_ascii(shown), shown);  // escaping twice changes nothing
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core
