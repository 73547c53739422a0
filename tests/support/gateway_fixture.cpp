#include "tests/support/gateway_fixture.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"

namespace eip2mqtt::test {

TempDir::TempDir() {
    char name[] = "/tmp/eip2mqtt-test-XXXXXX";
    if (::mkdtemp(name) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = name;
}

TempDir::~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
}

std::string TempDir::write(const std::string& name, const std::string& content) const {
    const std::string file = path_ + "/" + name;
    std::ofstream(file) << content;
    return file;
}

namespace {

/// A mapping's keys (indented by two spaces, the first by none) as the item of a list.
std::string as_list_item(const std::string& keys) {
    std::string out = "  - ";
    for (std::size_t at = 0; at < keys.size();) {
        const auto end = keys.find('\n', at);
        const auto line = keys.substr(at, end == std::string::npos ? end : end - at + 1);
        out += (at == 0 ? "" : "  ") + line;
        at = end == std::string::npos ? keys.size() : end + 1;
    }
    return out;
}

}  // namespace

void GatewayTest::start(const std::string& exchanges_yaml, const std::string& mqtt_extra,
                        GatewayOptions options) {
    options_ = std::move(options);
    broker_ = std::make_unique<Mosquitto>(options_.broker);
    if (udp_port_ == 0) udp_port_ = free_udp_port();
    udp_ = std::make_unique<UdpClient>();
    std::string url = options_.secure ? broker_->secure_url() : broker_->url();
    if (options_.url_through) url = options_.url_through(broker_->port());
    if (!options_.more_urls.empty()) {
        url = "[ \"" + url + "\"";
        for (const auto& more : options_.more_urls) url += ", \"" + more + "\"";
        url += " ]";
    }
    const std::string mqtt = "  url: " + url +
                             "\n"
                             "  base_topic: test\n"
                             "  qos: 1\n"
                             "  metrics_interval_s: 1\n" +
                             mqtt_extra;
    const std::string config =
        "gateway:\n"
        "  id: test-gw\n"
        "  state_dir: " +
        dir_.path() +
        "/state\n"
        "  log_level: debug\n"
        "mqtt:\n" +
        (options_.more_connections.empty()
             ? mqtt
             : as_list_item("name: site\n" + mqtt) + options_.more_connections) +
        "eip:\n"
        "  bind: 127.0.0.1\n"
        "  port: " +
        std::to_string(udp_port_) + "\n" + options_.eip_extra + options_.sections + "exchanges:\n" +
        exchanges_yaml;
    config_path_ = dir_.write("gateway.yaml", config);
    recorder_ = std::make_unique<MqttRecorder>(broker_->url(), std::vector<std::string>{"#"});
    start_gateway();
}

void GatewayTest::start_gateway() {
    const std::size_t from = recorder_->count();
    auto env = gateway_env_;
    env.insert(options_.env.begin(), options_.env.end());
    gateway_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{gateway_binary(), "run", "-c", config_path_}, std::move(env));
    if (options_.wait_online) wait_online(from);
}

void GatewayTest::wait_online(std::size_t from) {
    // After an outage the gateway tries the broker again at most every 30 s (the client's
    // max_backoff): a broker back after a long outage may wait that long for it.
    const auto online = recorder_->wait_for_message(
        availability_topic(), [](const std::string& p) { return p == "online"; },
        std::chrono::seconds(60), from);
    ASSERT_TRUE(online.has_value()) << "gateway never came online; its output:\n"
                                    << (gateway_ ? gateway_->output() : "");
}

void GatewayTest::rewrite_exchanges(const std::string& exchanges_yaml) {
    std::ifstream in(config_path_);
    std::stringstream text;
    text << in.rdbuf();
    const auto content = text.str();
    std::ofstream(config_path_) << content.substr(0, content.find("exchanges:\n")) +
                                       "exchanges:\n" + exchanges_yaml;
}

void GatewayTest::TearDown() {
    if (HasFailure() && gateway_) {
        std::cerr << "--- gateway output ---\n" << gateway_->output() << "--- end ---\n";
    }
    gateway_.reset();
    recorder_.reset();
    broker_.reset();
}

std::string GatewayTest::write_result(const std::string& set_suffix, const std::string& payload) {
    const auto from = recorder_->count();
    recorder_->publish(topic(set_suffix), payload);
    const auto result = recorder_->wait_for_message(topic(set_suffix + "/result"), nullptr,
                                                    std::chrono::seconds(10), from);
    EXPECT_TRUE(result.has_value()) << "no result on " << set_suffix << "/result";
    return result ? result->payload : std::string();
}

Received GatewayTest::expect_field(const std::string& topic, const std::string& field,
                                   const std::string& expected, std::size_t from) {
    const auto message = recorder_->wait_for_message(
        topic,
        [&](const std::string& payload) {
            const auto json = nlohmann::json::parse(payload, nullptr, false);
            return json.is_object() && json.contains(field) && json[field].dump() == expected;
        },
        std::chrono::seconds(10), from);
    if (!message) {
        std::string seen;
        for (const auto& m : recorder_->messages_on(topic)) seen += "  " + m.payload + "\n";
        ADD_FAILURE() << "no message on " << topic << " with " << field << "=" << expected
                      << "; seen:\n"
                      << seen;
        return {};
    }
    return *message;
}

}  // namespace eip2mqtt::test
