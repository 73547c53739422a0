// The Debian package tools/package.sh builds from the binary under test (never a second build):
// its files, conffiles, stripped binary, man page and unit, and what lintian says of it.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string last_line(const std::string& output) {
    std::istringstream lines(output);
    std::string line;
    std::string last;
    while (std::getline(lines, line)) {
        if (!line.empty()) last = line;
    }
    return last;
}

/// Runs `command` through sh, for pipes and environment variables.
RunResult shell(const std::string& command, std::chrono::milliseconds timeout = 60s) {
    return run_command({"/bin/sh", "-c", command}, timeout);
}

/// The version the binary under test reports: "eip2mqtt 0.1.0".
std::string binary_version() {
    const auto result = run_command({gateway_binary(), "--version"}, 10s);
    return result.output.substr(result.output.find(' ') + 1,
                                result.output.find('\n') - result.output.find(' ') - 1);
}

class PackageTest : public ::testing::Test {
protected:
    /// Builds the package into dir_ and extracts it into dir_/root.
    void SetUp() override {
        const std::string build_dir = std::filesystem::path(gateway_binary()).parent_path();
        const auto built =
            run_command({std::string(EIP2MQTT_SOURCE_DIR) + "/tools/package.sh", "--build-dir",
                         build_dir, "--out", dir_.path(), "--no-build"},
                        240s);
        ASSERT_EQ(built.status, 0) << built.output;
        deb_ = last_line(built.output);
        root_ = dir_.path() + "/root";
        const auto extracted = run_command({"/usr/bin/dpkg-deb", "-x", deb_, root_}, 60s);
        ASSERT_EQ(extracted.status, 0) << extracted.output;
    }

    void expect_name_and_fields() const;
    void expect_files_and_conffiles() const;
    void expect_stripped_binary() const;
    void expect_man_page() const;
    void expect_unit_verifies() const;

    std::string field(const std::string& name) const {
        return last_line(run_command({"/usr/bin/dpkg-deb", "-f", deb_, name}, 30s).output);
    }

    TempDir dir_;
    std::string deb_;
    std::string root_;
};

void PackageTest::expect_name_and_fields() const {
    const auto arch = last_line(run_command({"/usr/bin/dpkg", "--print-architecture"}, 10s).output);
    const auto version = binary_version();
    EXPECT_EQ(std::filesystem::path(deb_).filename().string(),
              "eip2mqtt_" + version + "_" + arch + ".deb");
    EXPECT_EQ(field("Package"), "eip2mqtt");
    EXPECT_EQ(field("Version"), version);
    EXPECT_EQ(field("Architecture"), arch);
    const auto depends = field("Depends");
    for (const auto* library :
         {"libc6", "libstdc++6", "libpaho-mqttpp3", "libyaml-cpp", "libpcap0.8", "libsqlite3-0"}) {
        EXPECT_NE(depends.find(library), std::string::npos) << depends;
    }
}

void PackageTest::expect_files_and_conffiles() const {
    for (const auto* path :
         {"/usr/bin/eip2mqtt", "/lib/systemd/system/eip2mqtt.service",
          "/etc/eip2mqtt/eip2mqtt.yaml", "/etc/eip2mqtt/turbine1.csv",
          "/usr/share/man/man1/eip2mqtt.1.gz", "/usr/share/doc/eip2mqtt/copyright",
          "/usr/share/doc/eip2mqtt/changelog.gz", "/usr/share/doc/eip2mqtt/README.md",
          "/usr/share/doc/eip2mqtt/docs/mqtt-api.md"}) {
        EXPECT_TRUE(std::filesystem::is_regular_file(root_ + path)) << path;
    }
    // The example is the one in the source tree, as it is.
    EXPECT_EQ(read_text(root_ + "/etc/eip2mqtt/eip2mqtt.yaml"),
              read_text(std::string(EIP2MQTT_SOURCE_DIR) + "/etc/eip2mqtt/eip2mqtt.yaml"));
    // The state directory is the unit's (StateDirectory=): the package ships none.
    EXPECT_FALSE(std::filesystem::exists(root_ + "/var")) << deb_;

    const auto control = dir_.path() + "/control";
    ASSERT_EQ(run_command({"/usr/bin/dpkg-deb", "-e", deb_, control}, 30s).status, 0);
    EXPECT_EQ(read_text(control + "/conffiles"),
              "/etc/eip2mqtt/eip2mqtt.yaml\n/etc/eip2mqtt/turbine1.csv\n");
    for (const auto* script : {"postinst", "prerm", "postrm"}) {
        const auto status = std::filesystem::status(control + "/" + script);
        EXPECT_NE(status.permissions() & std::filesystem::perms::owner_exec,
                  std::filesystem::perms::none)
            << script;
    }
}

void PackageTest::expect_stripped_binary() const {
    const auto binary = root_ + "/usr/bin/eip2mqtt";
    const auto sections = run_command({"/usr/bin/readelf", "-S", "--wide", binary}, 30s);
    ASSERT_EQ(sections.status, 0) << sections.output;
    EXPECT_EQ(sections.output.find(".debug_"), std::string::npos) << sections.output;
    EXPECT_EQ(sections.output.find(".symtab"), std::string::npos) << sections.output;
    EXPECT_LT(std::filesystem::file_size(binary), std::filesystem::file_size(gateway_binary()));
    const auto version = run_command({binary, "--version"}, 10s);
    EXPECT_EQ(version.status, 0) << version.output;
    EXPECT_EQ(version.output, "eip2mqtt " + binary_version() + "\n");
}

void PackageTest::expect_man_page() const {
    const auto page = root_ + "/usr/share/man/man1/eip2mqtt.1.gz";
    // Warnings go to stderr, the page to stdout.
    const auto warnings = shell("MANWIDTH=80 man --warnings -l '" + page + "' 2>&1 >/dev/null");
    EXPECT_EQ(warnings.status, 0) << warnings.output;
    EXPECT_EQ(warnings.output, "");
    const auto text = shell("MANWIDTH=80 man -l '" + page + "' 2>/dev/null");
    for (const auto* part : {"NAME", "SYNOPSIS", "eip2mqtt check", "CREDENTIALS_DIRECTORY",
                             "/etc/eip2mqtt/eip2mqtt.yaml", "EXIT STATUS"}) {
        EXPECT_NE(text.output.find(part), std::string::npos) << part << "\n" << text.output;
    }
}

void PackageTest::expect_unit_verifies() const {
    auto unit = read_text(root_ + "/lib/systemd/system/eip2mqtt.service");
    for (const auto* key : {"ExecStart=/usr/bin/eip2mqtt run -c /etc/eip2mqtt/eip2mqtt.yaml",
                            "StateDirectory=eip2mqtt",
                            "Documentation=man:eip2mqtt(1) "
                            "file:///usr/share/doc/eip2mqtt/README.md"}) {
        EXPECT_NE(unit.find(key), std::string::npos) << key << "\n" << unit;
    }
    EXPECT_EQ(unit.find("/usr/local"), std::string::npos) << unit;
    // The unit names /usr/bin/eip2mqtt, which this machine may lack: point it at the extracted
    // one, and the man page lookup at the extracted pages, so both are checked.
    unit = std::regex_replace(unit, std::regex("/usr/bin/eip2mqtt"), root_ + "/usr/bin/eip2mqtt");
    TempDir units;
    const auto path = units.write("eip2mqtt.service", unit);
    const auto result = run_command({"/usr/bin/env", "MANPATH=" + root_ + "/usr/share/man",
                                     "/usr/bin/systemd-analyze", "verify", path},
                                    60s);
    EXPECT_EQ(result.status, 0) << result.output;
}

// One test for all of these, since each test builds the package again.
TEST_F(PackageTest, HoldsTheStrippedBinaryUnitConfigurationAndManPage) {
    expect_name_and_fields();
    expect_files_and_conffiles();
    expect_stripped_binary();
    expect_man_page();
    expect_unit_verifies();
}

/// lintian reports no error, and the README explains every warning it leaves.
TEST_F(PackageTest, LintianFindsNoErrorAndTheReadmeExplainsEachWarning) {
    const auto result = run_command(
        {"/usr/bin/lintian", "--fail-on", "error", "--tag-display-limit", "0", deb_}, 110s);
    EXPECT_EQ(result.status, 0) << result.output;
    const auto readme = read_text(std::string(EIP2MQTT_SOURCE_DIR) + "/README.md");
    std::set<std::string> warnings;
    const std::regex tag(R"(^([EW]): eip2mqtt[^:]*: ([a-z0-9.+-]+))");
    std::istringstream lines(result.output);
    for (std::string line; std::getline(lines, line);) {
        std::smatch match;
        if (!std::regex_search(line, match, tag)) continue;
        EXPECT_NE(match[1], "E") << line;
        warnings.insert(match[2]);
    }
    for (const auto& warning : warnings) {
        EXPECT_NE(readme.find("`" + warning + "`"), std::string::npos)
            << "lintian warns " << warning << ", which the README does not explain";
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
