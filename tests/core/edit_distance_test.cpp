#include "eip2mqtt/core/edit_distance.hpp"

#include <gtest/gtest.h>

namespace eip2mqtt::core {
namespace EIP2MQTT_THIS_FILE {

TEST(EditDistance, CountsInsertionsRemovalsAndReplacements) {
    EXPECT_EQ(edit_distance("real", "real"), 0u);
    EXPECT_EQ(edit_distance("reel", "real"), 1u);   // replaced
    EXPECT_EQ(edit_distance("rea", "real"), 1u);    // inserted
    EXPECT_EQ(edit_distance("reall", "real"), 1u);  // removed
    EXPECT_EQ(edit_distance("float", "real"), 4u);
    EXPECT_EQ(edit_distance("", "dint"), 4u);
    EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core
