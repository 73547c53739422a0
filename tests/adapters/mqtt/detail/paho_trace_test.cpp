#include "adapters/mqtt/detail/paho_trace.hpp"

#include <MQTTAsync.h>
#include <gtest/gtest.h>

#include <mutex>
#include <vector>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

std::mutex traced_mutex;
std::vector<int> traced_levels;

void record(enum MQTTASYNC_TRACE_LEVELS level, char* /*message*/) {
    std::lock_guard lock(traced_mutex);
    traced_levels.push_back(level);
}

MQTTAsync create_client(const char* id) {
    MQTTAsync client = nullptr;
    EXPECT_EQ(
        ::MQTTAsync_create(&client, "tcp://127.0.0.1:1", id, MQTTCLIENT_PERSISTENCE_NONE, nullptr),
        MQTTASYNC_SUCCESS);
    return client;
}

/// Paho starts its trace afresh, with a banner at the lowest level, whenever its first client is
/// created: one client kept for the test's length leaves only what the functions trace.
struct KeptClient {
    KeptClient() : client(create_client("trace-test-kept")) {}
    ~KeptClient() { ::MQTTAsync_destroy(&client); }
    MQTTAsync client;
};

/// The levels of the entries Paho traced while it created and destroyed a client.
std::vector<int> levels_traced_by_a_client() {
    {
        std::lock_guard lock(traced_mutex);
        traced_levels.clear();
    }
    ::MQTTAsync_setTraceCallback(record);
    MQTTAsync client = create_client("trace-test");
    ::MQTTAsync_destroy(&client);
    ::MQTTAsync_setTraceCallback(nullptr);
    std::lock_guard lock(traced_mutex);
    return traced_levels;
}

bool any_below_errors(const std::vector<int>& levels) {
    for (const int level : levels) {
        if (level < MQTTASYNC_TRACE_ERROR) return true;
    }
    return false;
}

TEST(QuietPahoTraceTest, LeavesOnlyErrorsInPahosTraceWhenNoTraceWasAskedFor) {
    const KeptClient kept;
    // Paho's own default, as Debian builds it: every function's entry is traced.
    ::MQTTAsync_setTraceLevel(MQTTASYNC_TRACE_MINIMUM);
    ASSERT_TRUE(any_below_errors(levels_traced_by_a_client()));

    EXPECT_TRUE(quiet_paho_trace(nullptr));
    EXPECT_FALSE(any_below_errors(levels_traced_by_a_client()));
    EXPECT_TRUE(quiet_paho_trace(""));
}

TEST(QuietPahoTraceTest, KeepsPahosLevelWhenTheEnvironmentAsksForATrace) {
    const KeptClient kept;
    ::MQTTAsync_setTraceLevel(MQTTASYNC_TRACE_MINIMUM);
    EXPECT_FALSE(quiet_paho_trace("ON"));
    EXPECT_TRUE(any_below_errors(levels_traced_by_a_client()));
    quiet_paho_trace(nullptr);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
