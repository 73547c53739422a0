#include "eip2mqtt/core/out_of_line.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>

namespace eip2mqtt::core {
namespace EIP2MQTT_THIS_FILE {

struct Settings {
    std::string unit;
    int limit = 0;

    friend bool operator==(const Settings&, const Settings&) = default;
};

TEST(OutOfLine, ReadsTheDefaultWithoutAllocating) {
    const OutOfLine<Settings> box;
    EXPECT_EQ(box.get(), Settings{});
    EXPECT_FALSE(box.allocated());
}

TEST(OutOfLine, CostsOnePointer) { EXPECT_EQ(sizeof(OutOfLine<Settings>), sizeof(void*)); }

TEST(OutOfLine, WritesAllocateOnce) {
    OutOfLine<Settings> box;
    box.mutable_get().unit = "bar";
    const Settings* first = &box.get();
    box.mutable_get().limit = 3;
    EXPECT_TRUE(box.allocated());
    EXPECT_EQ(&box.get(), first);
    EXPECT_EQ(box.get(), (Settings{"bar", 3}));
}

TEST(OutOfLine, CopiesAreIndependent) {
    OutOfLine<Settings> a;
    a.mutable_get().unit = "bar";
    OutOfLine<Settings> b = a;
    b.mutable_get().unit = "psi";
    EXPECT_EQ(a.get().unit, "bar");
    EXPECT_EQ(b.get().unit, "psi");
    OutOfLine<Settings> c;
    c = a;
    EXPECT_NE(&c.get(), &a.get());
    EXPECT_EQ(c.get().unit, "bar");
    c = OutOfLine<Settings>{};  // assigning an empty one frees the value
    EXPECT_FALSE(c.allocated());
}

TEST(OutOfLine, MovedFromReadsTheDefault) {
    OutOfLine<Settings> a;
    a.mutable_get().limit = 7;
    const OutOfLine<Settings> b = std::move(a);
    EXPECT_EQ(b.get().limit, 7);
    EXPECT_EQ(a.get(), Settings{});  // NOLINT(bugprone-use-after-move): specified above
}

TEST(OutOfLine, EqualityComparesContents) {
    OutOfLine<Settings> empty;
    OutOfLine<Settings> written_default;
    written_default.mutable_get();
    EXPECT_EQ(empty, written_default);
    OutOfLine<Settings> a;
    a.mutable_get().unit = "bar";
    OutOfLine<Settings> b;
    b.mutable_get().unit = "bar";
    EXPECT_EQ(a, b);
    b.mutable_get().limit = 1;
    EXPECT_NE(a, b);
    EXPECT_NE(a, empty);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core
