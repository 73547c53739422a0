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
    static constexpr char alphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const auto path = temp_file(".b64");
    {
        std::ofstream file(path);
        for (const auto& bytes : payloads) {
            std::string line;
            for (std::size_t i = 0; i < bytes.size(); i += 3) {
                std::uint32_t n = static_cast<std::uint8_t>(bytes[i]) << 16;
                if (i + 1 < bytes.size()) n |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
                if (i + 2 < bytes.size()) n |= static_cast<std::uint8_t>(bytes[i + 2]);
                line += alphabet[(n >> 18) & 63];
                line += alphabet[(n >> 12) & 63];
                line += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
                line += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
            }
            file << line << '\n';
        }
    }
    const auto result =
        run_command({EIP2MQTT_NODE, EIP2MQTT_TAHU_SCRIPT, "decode-lines", path.string()},
                    std::chrono::seconds(120));
    std::filesystem::remove(path);
    EXPECT_EQ(result.status, 0) << result.output;
    std::vector<nlohmann::json> out;
    std::istringstream lines(result.output);
    for (std::string line; std::getline(lines, line);) {
        out.push_back(nlohmann::json::parse(line, nullptr, false));
        EXPECT_FALSE(out.back().is_discarded()) << line;
    }
    EXPECT_EQ(out.size(), payloads.size()) << result.output.substr(0, 2000);
    // A caller reads out[i] for each of its payloads.
    out.resize(payloads.size(), nlohmann::json::object());
    return out;
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

nlohmann::json tahu_metric(const nlohmann::json& payload, const std::string& name) {
    if (payload.is_object() && payload.contains("metrics") && payload["metrics"].is_array()) {
        for (const auto& m : payload["metrics"]) {
            if (m.is_object() && m.value("name", "") == name) return m;
        }
    }
    ADD_FAILURE() << "no metric " << name << " in " << payload.dump();
    return nlohmann::json::object();
}

}  // namespace eip2mqtt::test
