// docker/: no Docker engine runs here, so what can drift without one is checked against the
// binary under test and the one example configuration: the runtime image's libraries, the
// configuration compose runs, the health check's address, the host network.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_binary.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const std::string source_dir = EIP2MQTT_SOURCE_DIR;

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The Debian package that ships each library for this architecture, from dpkg's database
/// in one query ("libfmt9"; libm.so.6 is libc6's, not libc6-i386's).
std::map<std::string, std::string> packages_of(const std::vector<std::string>& libraries) {
    const auto multiarch =
        run_command({"/usr/bin/dpkg-architecture", "-qDEB_HOST_MULTIARCH"}, 30s).output;
    const auto directory = multiarch.substr(0, multiarch.find('\n'));
    std::vector<std::string> query{"/usr/bin/dpkg", "-S"};
    for (const auto& library : libraries) query.push_back("*/" + directory + "/" + library);
    const auto result = run_command(query, 60s);
    std::map<std::string, std::string> packages;
    const std::regex line(R"(([^:,\s]+)[^\n]*: (\S+)\n)");
    for (std::sregex_iterator it(result.output.begin(), result.output.end(), line), end; it != end;
         ++it) {
        const std::string path = (*it)[2];
        packages.emplace(path.substr(path.rfind('/') + 1), (*it)[1]);
    }
    return packages;
}

/// Whether `word` stands alone in `text`, between blanks or line ends.
bool has_word(const std::string& text, const std::string& word) {
    const auto escaped = std::regex_replace(word, std::regex(R"([.^$|()\[\]{}*+?\\/])"), R"(\$&)");
    return std::regex_search(text, std::regex("(^|\\s)" + escaped + "(\\s|$)"));
}

TEST(DockerFiles, TheRuntimeImageInstallsEveryLibraryTheBinaryLinks) {
    const auto dockerfile = read_text(source_dir + "/docker/Dockerfile");
    const auto runtime_stage = dockerfile.substr(dockerfile.rfind("\nFROM "));
    // In debian:12 itself; the sanitizers' runtimes belong to the test builds, not the image's.
    const std::set<std::string> in_base_image{"libc6", "libstdc++6", "libgcc-s1"};
    const std::regex sanitizer_runtime("lib(a|ub|l|t)san\\.so.*");
    std::vector<std::string> libraries;
    for (const auto& library : needed_libraries(gateway_binary())) {
        if (!std::regex_match(library, sanitizer_runtime)) libraries.push_back(library);
    }
    ASSERT_FALSE(libraries.empty());
    const auto packages = packages_of(libraries);
    for (const auto& library : libraries) {
        ASSERT_TRUE(packages.contains(library)) << library << " is in no Debian package";
        const auto& package = packages.at(library);
        if (in_base_image.contains(package)) continue;
        EXPECT_TRUE(has_word(runtime_stage, package))
            << library << " comes with " << package << ", which the runtime stage lacks";
    }
}

TEST(DockerFiles, TheRuntimeImageInstallsTheLibrariesLoadedWhereUsed) {
    // Loaded with dlopen (by a journal, by sniff), so the binary does not name them.
    const auto dockerfile = read_text(source_dir + "/docker/Dockerfile");
    const auto runtime_stage = dockerfile.substr(dockerfile.rfind("\nFROM "));
    const std::vector<std::string> libraries{"libsqlite3.so.0", "libpcap.so.0.8"};
    const auto packages = packages_of(libraries);
    for (const auto& library : libraries) {
        ASSERT_TRUE(packages.contains(library)) << library << " is in no Debian package";
        EXPECT_TRUE(has_word(runtime_stage, packages.at(library)))
            << library << " comes with " << packages.at(library) << ", which the runtime lacks";
    }
}

TEST(DockerFiles, ComposeRunsTheOneExampleConfigurationOnTheHostsNetwork) {
    const auto compose = read_text(source_dir + "/docker/compose.yaml");
    // One example: no configuration of docker/'s own to drift from it.
    for (const auto& entry : std::filesystem::directory_iterator(source_dir + "/docker")) {
        const auto name = entry.path().filename().string();
        EXPECT_TRUE(name == "Dockerfile" || name == "compose.yaml") << name;
    }
    EXPECT_NE(compose.find("../etc/eip2mqtt:/etc/eip2mqtt:ro"), std::string::npos) << compose;
    EXPECT_NE(compose.find(R"("-c", "/etc/eip2mqtt/eip2mqtt.yaml")"), std::string::npos);
    const auto example = source_dir + "/etc/eip2mqtt/eip2mqtt.yaml";
    const auto check = run_command({gateway_binary(), "check", "-c", example}, 30s);
    EXPECT_EQ(check.status, 0) << check.output;

    // Broadcast and multicast never cross a bridge: each service on the host's network, and
    // each one that runs for good restarted.
    const std::regex service(R"(\n  ([a-z]+):\n)");
    int services = 0;
    for (std::sregex_iterator it(compose.begin(), compose.end(), service), end; it != end; ++it) {
        ++services;
    }
    auto count = [&](const std::string& text) {
        int n = 0;
        for (auto at = compose.find(text); at != std::string::npos;
             at = compose.find(text, at + 1)) {
            ++n;
        }
        return n;
    };
    EXPECT_EQ(services, 3) << compose;
    EXPECT_EQ(count("\n    network_mode: host\n"), services) << compose;
    EXPECT_EQ(count("\n    restart: unless-stopped\n"), services) << compose;
    EXPECT_EQ(compose.find("ports:"), std::string::npos) << compose;
}

TEST(DockerFiles, TheHealthCheckAsksTheExamplesMetricsListener) {
    const auto dockerfile = read_text(source_dir + "/docker/Dockerfile");
    const auto example = read_text(source_dir + "/etc/eip2mqtt/eip2mqtt.yaml");
    std::smatch listen;
    ASSERT_TRUE(std::regex_search(example, listen, std::regex(R"(\n  listen: ([0-9.]+:[0-9]+))")))
        << "the example serves no metrics listener";
    EXPECT_NE(dockerfile.find("EIP2MQTT_HEALTH_URL=http://" + listen[1].str() + "/healthz"),
              std::string::npos)
        << dockerfile;
    EXPECT_NE(dockerfile.find("HEALTHCHECK "), std::string::npos);
    EXPECT_NE(dockerfile.find(" AS build"), std::string::npos);
    EXPECT_NE(dockerfile.find("--strip-unneeded"), std::string::npos);
    EXPECT_NE(dockerfile.find("USER eip2mqtt"), std::string::npos);
    const auto ignore = read_text(source_dir + "/.dockerignore");
    for (const auto* excluded : {".git", "build*/", "**/node_modules/"}) {
        EXPECT_TRUE(has_word(ignore, excluded)) << excluded;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
