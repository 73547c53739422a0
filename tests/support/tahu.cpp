#include "tests/support/tahu.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/child_process.hpp"

namespace eip2mqtt::test {
namespace {

std::filesystem::path temp_file(const char* suffix) {
    static std::atomic<int> next{0};
    return std::filesystem::temp_directory_path() /
           ("eip2mqtt_tahu_" + std::to_string(::getpid()) + "_" + std::to_string(next++) + suffix);
}

}  // namespace

nlohmann::json tahu_decode(const std::string& bytes) {
    const auto path = temp_file(".bin");
    std::ofstream(path, std::ios::binary) << bytes;
    const auto result = run_command({EIP2MQTT_NODE, EIP2MQTT_TAHU_SCRIPT, "decode", path.string()},
                                    std::chrono::seconds(60));
    std::filesystem::remove(path);
    EXPECT_EQ(result.status, 0) << result.output;
    auto json = nlohmann::json::parse(result.output, nullptr, false);
    EXPECT_FALSE(json.is_discarded()) << result.output;
    return json;
}

std::vector<nlohmann::json> tahu_decode_all(const std::vector<std::string>& payloads) {
    if (payloads.empty()) return {};
    std::vector<std::string> argv{EIP2MQTT_NODE, EIP2MQTT_TAHU_SCRIPT, "decode-all"};
    std::vector<std::filesystem::path> files;
    for (const auto& bytes : payloads) {
        files.push_back(temp_file(".bin"));
        std::ofstream(files.back(), std::ios::binary) << bytes;
        argv.push_back(files.back().string());
    }
    const auto result = run_command(argv, std::chrono::seconds(120));
    for (const auto& file : files) std::filesystem::remove(file);
    EXPECT_EQ(result.status, 0) << result.output;
    const auto json = nlohmann::json::parse(result.output, nullptr, false);
    if (!json.is_array() || json.size() != payloads.size()) {
        ADD_FAILURE() << "Tahu decoded " << payloads.size()
                      << " payloads into: " << result.output.substr(0, 2000);
        return std::vector<nlohmann::json>(payloads.size(), nlohmann::json::object());
    }
    return {json.begin(), json.end()};
}

std::string tahu_encode(const nlohmann::json& payload) {
    const auto input = temp_file(".json");
    const auto output = temp_file(".bin");
    std::ofstream(input) << payload.dump();
    const auto result = run_command(
        {EIP2MQTT_NODE, EIP2MQTT_TAHU_SCRIPT, "encode", input.string(), output.string()},
        std::chrono::seconds(60));
    EXPECT_EQ(result.status, 0) << result.output;
    std::ifstream file(output, std::ios::binary);
    std::stringstream bytes;
    bytes << file.rdbuf();
    std::filesystem::remove(input);
    std::filesystem::remove(output);
    return bytes.str();
}

}  // namespace eip2mqtt::test
