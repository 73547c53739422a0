// What the binary loads at start: libraries only some commands use are loaded by them, so that
// a running gateway keeps none of their pages resident (docs/performance.md).

#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_binary.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

TEST(LinkedLibraries, SqliteIsLoadedByTheJournalNotWithTheGateway) {
    const auto libraries = needed_libraries(gateway_binary());
    ASSERT_FALSE(libraries.empty());
    for (const auto& library : libraries) {
        EXPECT_EQ(library.find("libsqlite3"), std::string::npos) << library;
    }
}

TEST(LinkedLibraries, LibpcapIsLoadedBySniffNotWithTheGateway) {
    const auto libraries = needed_libraries(gateway_binary());
    ASSERT_FALSE(libraries.empty());
    for (const auto& library : libraries) {
        EXPECT_EQ(library.find("libpcap"), std::string::npos) << library;
        EXPECT_EQ(library.find("libdbus"), std::string::npos) << library;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
