#include "eip2mqtt/core/printable.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::core {
namespace {

TEST(Printable, ControlBytesAreEscapedAndLongTextIsCut) {
    EXPECT_EQ(printable("plain/topic"), "plain/topic");
    EXPECT_EQ(printable("a\nb\x01\x7f"), "a\\x0ab\\x01\\x7f");
    EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
    EXPECT_EQ(printable(std::string(300, 'x'), 4), "xxxx...");
    EXPECT_EQ(printable("PRESSÃO"), "PRESSÃO");
}

}  // namespace
}  // namespace eip2mqtt::core
