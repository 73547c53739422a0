#include "eip2mqtt/core/wire/drop_reason.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace eip2mqtt::core::wire {
namespace EIP2MQTT_THIS_FILE {

TEST(DropReason, NamesAreTheMetricLabels) {
    EXPECT_EQ(to_string(DropReason::too_short), "too_short");
    EXPECT_EQ(to_string(DropReason::not_data_pdu), "not_data_pdu");
    EXPECT_EQ(to_string(DropReason::too_long), "too_long");
    EXPECT_EQ(to_string(DropReason::unknown_exchange), "unknown_exchange");
    EXPECT_EQ(to_string(DropReason::wrong_source), "wrong_source");
    EXPECT_EQ(to_string(DropReason::no_data), "no_data");
    EXPECT_EQ(to_string(DropReason::signature_mismatch), "signature_mismatch");
    EXPECT_EQ(to_string(DropReason::length_mismatch), "length_mismatch");
    EXPECT_EQ(to_string(DropReason::duplicate), "duplicate");
    EXPECT_EQ(to_string(DropReason::out_of_order), "out_of_order");
}

TEST(DropReason, AllReasonsAreListedOnceWithDistinctNames) {
    std::set<DropReason> reasons(all_drop_reasons.begin(), all_drop_reasons.end());
    std::set<std::string> names;
    for (DropReason reason : all_drop_reasons) names.emplace(to_string(reason));
    EXPECT_EQ(reasons.size(), drop_reason_count);
    EXPECT_EQ(names.size(), drop_reason_count);
    EXPECT_EQ(static_cast<std::size_t>(DropReason::out_of_order) + 1, drop_reason_count);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::wire
