// `eip2mqtt dissector`: the plugin of a configuration written to its file and said so with its
// counts; a configuration error or a file it cannot write exits 1 with the reason.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "eip2mqtt/app/cli/commands.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

const char* two_exchanges =
    "mqtt:\n  url: tcp://a:1883\neip:\n  port: 18300\nexchanges:\n"
    "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8,\n"
    "      tags: [ { name: Speed, address: \"0.0\", type: byte } ] }\n"
    "  - { name: other, producer_id: 10.0.0.1, exchange_id: 2, length: 8,\n"
    "      tags: [ { name: A, address: \"0.0\", type: byte }, { name: B, address: \"1.0\", "
    "type: byte } ] }\n";

std::string read(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

TEST(Dissector, WritesThePluginAndSaysWhatItDecodes) {
    test::TempDir dir;
    const DissectorOptions options{dir.write("gw.yaml", two_exchanges), dir.path() + "/gw.lua"};
    std::ostringstream out;
    std::ostringstream err;
    ASSERT_EQ(run_dissector(options, out, err), 0) << err.str();
    EXPECT_EQ(out.str(), "wrote " + options.output +
                             ": 2 exchanges, 3 tags (tshark -X lua_script:" + options.output +
                             ", or copy it to ~/.local/lib/wireshark/plugins/)\n");
    EXPECT_TRUE(err.str().empty());
    const auto plugin = read(options.output);
    EXPECT_NE(plugin.find("Speed"), std::string::npos);
    EXPECT_NE(plugin.find("18300"), std::string::npos);
}

TEST(Dissector, OneExchangeAndOneTagAreSingular) {
    test::TempDir dir;
    const DissectorOptions options{
        dir.write("gw.yaml",
                  "mqtt:\n  url: tcp://a:1883\nexchanges:\n"
                  "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8,\n"
                  "      tags: [ { name: Speed, address: \"0.0\", type: byte } ] }\n"),
        dir.path() + "/gw.lua"};
    std::ostringstream out;
    std::ostringstream err;
    ASSERT_EQ(run_dissector(options, out, err), 0) << err.str();
    EXPECT_NE(out.str().find(": 1 exchange, 1 tag ("), std::string::npos) << out.str();
}

TEST(Dissector, AConfigurationErrorWritesNothing) {
    test::TempDir dir;
    const DissectorOptions options{dir.write("gw.yaml", "mqtt:\n  url: tcp://a:1883\n"),
                                   dir.path() + "/gw.lua"};
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(run_dissector(options, out, err), 1);
    EXPECT_TRUE(out.str().empty());
    EXPECT_NE(err.str().find(" error(s)\n"), std::string::npos) << err.str();
    EXPECT_FALSE(std::ifstream(options.output).good());
}

TEST(Dissector, AFileItCannotWriteIsAnError) {
    test::TempDir dir;
    const DissectorOptions options{dir.write("gw.yaml", two_exchanges),
                                   dir.path() + "/missing/gw.lua"};
    std::ostringstream out;
    std::ostringstream err;
    EXPECT_EQ(run_dissector(options, out, err), 1);
    EXPECT_EQ(err.str(), "eip2mqtt: cannot write " + options.output + "\n");
    EXPECT_TRUE(out.str().empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
