#include "tests/support/dissector_values.hpp"

#include <chrono>
#include <cstdio>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_binary.hpp"

namespace eip2mqtt::test {

std::string write_dissector(const std::string& config_path, const std::string& dir) {
    const auto plugin = dir + "/eip2mqtt.lua";
    const auto result = run_command(
        {gateway_binary(), "dissector", "-c", config_path, "-o", plugin}, std::chrono::seconds(30));
    EXPECT_EQ(result.status, 0) << result.output;
    return plugin;
}

std::string as_tshark_prints(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    return text;
}

::testing::AssertionResult agree(core::plan::TagType type, const std::string& shown,
                                 const nlohmann::json& published) {
    using core::plan::TagType;
    std::string expected;
    switch (type) {
        case TagType::bit:
            expected = published.get<bool>() ? "1" : "0";
            break;
        case TagType::real:
            expected = as_tshark_prints(published.get<float>(), 6);
            break;
        case TagType::lreal:
            expected = as_tshark_prints(published.get<double>(), 15);
            break;
        default:
            expected = published.dump();
            break;
    }
    if (shown == expected) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << "tshark shows " << shown << ", MQTT has " << published << " (" << expected << ")";
}

}  // namespace eip2mqtt::test
