#pragma once
/// An integration-test harness: a real Mosquitto on a free port, the real eip2mqtt binary
/// running a configuration written by the test, a recorder subscribed to everything (the base
/// topic, and the clients' own response topics outside it), and a UDP socket to feed the
/// gateway.

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {

/// A temporary directory removed (with its content) at destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    const std::string& path() const { return path_; }
    /// Writes `content` to `name` inside the directory; returns the full path.
    std::string write(const std::string& name, const std::string& content) const;

private:
    std::string path_;
};

/// Optional settings of GatewayTest::start; the defaults give the plain set-up.
struct GatewayOptions {
    MosquittoOptions broker;  ///< how the broker is started
    /// The gateway connects to the broker's secure listener (Mosquitto::secure_url()) instead
    /// of the plain one; the recorder always uses the plain one.
    bool secure = false;
    /// Brokers after the test's own in `mqtt.url` (tcp://127.0.0.1:PORT...): the gateway gets
    /// a list, the test's broker first.
    std::vector<std::string> more_urls;
    /// Connections after the test's own (`mqtt` as a list): list items, `  - name: …` and
    /// their keys indented by four spaces. The test's own connection is named `site`.
    std::string more_connections;
    /// When set, the gateway's URL for the broker on `port` (a relay or a proxy in between).
    std::function<std::string(std::uint16_t port)> url_through;
    std::map<std::string, std::string> env;  ///< added to the gateway's environment
    /// Top-level sections added to the configuration (`sparkplug:` ...), as YAML text.
    std::string sections;
    /// Keys added to the `eip` section (`multicast:` ...), indented by two spaces.
    std::string eip_extra;
    /// false: start() and start_gateway() return once the process is started, for tests
    /// where the gateway must not come online.
    bool wait_online = true;
};

class GatewayTest : public ::testing::Test {
protected:
    static constexpr const char* base_topic = "test";

    /// Starts broker, gateway and recorder. `exchanges_yaml` is the text of the `exchanges:`
    /// list (indented by two spaces); `mqtt_extra` adds keys to the mqtt section.
    void start(const std::string& exchanges_yaml, const std::string& mqtt_extra = "",
               GatewayOptions options = {});
    /// Starts only the gateway again (after stop_gateway or a kill), same configuration.
    void start_gateway();
    /// Waits for `online` on the availability topic, counting only messages after `from`.
    void wait_online(std::size_t from = 0);
    /// Rewrites the configuration file with other exchanges, keeping the rest (for a reload).
    void rewrite_exchanges(const std::string& exchanges_yaml);
    void TearDown() override;

    std::string topic(const std::string& suffix) const {
        return std::string(base_topic) + "/" + suffix;
    }
    std::string availability_topic() const { return topic("_gateway/test-gw/state"); }
    std::string metrics_topic() const { return topic("_gateway/test-gw/metrics"); }
    /// Sends a datagram to the gateway's UDP port.
    void send(const std::vector<std::byte>& datagram) { udp_->send_to(udp_port_, datagram); }
    /// Waits for the next message on `topic` (after index `from`) whose JSON payload has
    /// `field` equal to the JSON text `expected`; fails the test on timeout.
    Received expect_field(const std::string& topic, const std::string& field,
                          const std::string& expected, std::size_t from = 0);
    /// Publishes a write on `{base}/{set_suffix}` and returns the payload of its `/result`;
    /// empty, the test failed, when none comes within 10 s.
    std::string write_result(const std::string& set_suffix, const std::string& payload);

    TempDir dir_;
    std::unique_ptr<Mosquitto> broker_;
    std::unique_ptr<ChildProcess> gateway_;
    std::unique_ptr<MqttRecorder> recorder_;
    std::unique_ptr<UdpClient> udp_;
    std::uint16_t udp_port_ = 0;  ///< the gateway's EIP port; set before start() to choose it
    std::string config_path_;
    std::map<std::string, std::string> gateway_env_;  ///< added to the gateway's environment
    GatewayOptions options_;                          ///< as given to start()
};

}  // namespace eip2mqtt::test
