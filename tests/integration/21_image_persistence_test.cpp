// Produced images on a state directory that fills up or loses its files: a write answered
// plain ok is never undone by a restart or a reload; one whose image cannot be saved is
// answered so (refused, or "saved":false when it was sent already), shown in `_status`, and
// counted in the metrics topic and Prometheus. The full disk is a real tmpfs.

#include <signal.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"
#include "tests/support/tmpfs.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using nlohmann::json;
using namespace std::chrono_literals;

const json ok = {{"ok", true}};

/// A produced exchange with one writable dint VALUE at 0.0, sent to 127.0.0.1:`port`.
std::string produced(const std::string& name, std::uint32_t id, std::uint16_t port,
                     std::uint32_t period_ms = 20) {
    return ExchangeYaml::produce(name, "10.1.2.3", id, "127.0.0.1:" + std::to_string(port))
        .period_ms(period_ms)
        .tag("VALUE", "0.0", "dint", "writable: true")
        .str();
}

class ImagePersistenceTest : public GatewayTest {
protected:
    void SetUp() override {
        // The state directory the fixture configures, on a tmpfs of its own: 256 KiB.
        disk_ = std::make_unique<Tmpfs>(256 * 1024, false, dir_.path() + "/state");
        if (!disk_->mounted()) GTEST_SKIP() << disk_->error();
    }
    void TearDown() override {
        GatewayTest::TearDown();  // the gateway first: it holds files on the tmpfs
        disk_.reset();
    }

    /// VALUE in the next datagram of `exchange_id` (the capture socket gets every exchange).
    std::int64_t next_value(std::uint32_t exchange_id = 10) {
        while (capture_.receive(0ms)) {
        }
        for (int i = 0; i < 1000; ++i) {
            const auto bytes = capture_.receive(5s);
            if (!bytes) break;
            if (core::wire::decode_header(*bytes).exchange_id != exchange_id) continue;
            return std::get<std::int64_t>(core::plan::decode_value(
                std::span(*bytes).subspan(32), core::plan::TagType::dint, {0, 0}));
        }
        ADD_FAILURE() << "no datagram of exchange " << exchange_id;
        return -1;
    }
    /// Writes VALUE of `exchange` and returns the result.
    json write(const std::string& exchange, std::int64_t value) {
        const auto result_topic = topic(exchange + "/VALUE/set/result");
        const auto from = recorder_->count();
        recorder_->publish(topic(exchange + "/VALUE/set"), std::to_string(value));
        const auto result = recorder_->wait_for_message(result_topic, nullptr, 10s, from);
        EXPECT_TRUE(result.has_value()) << "no result on " << result_topic;
        return result ? json::parse(result->payload) : json();
    }
    /// Waits for a `_status` of `exchange`, published after message `from`, with `field` equal
    /// to the JSON text `expected`.
    json status_with(const std::string& exchange, const std::string& field,
                     const std::string& expected, std::size_t from = 0) {
        const auto message = expect_field(topic(exchange + "/_status"), field, expected, from);
        return message.payload.empty() ? json() : json::parse(message.payload);
    }
    void reload_with(const std::string& exchanges) {
        rewrite_exchanges(exchanges);
        gateway_->signal(SIGHUP);  // once per test: the line below is this reload's
        ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();
    }
    void restart() {
        gateway_->signal(SIGKILL);
        gateway_->wait(5s);
        start_gateway();
    }

    std::unique_ptr<Tmpfs> disk_;
    UdpClient capture_;
};

TEST_F(ImagePersistenceTest, OnAFullDiskAWriteAnsweredOkSurvivesAReloadAndARestart) {
    start(produced("sp", 10, capture_.port()));
    EXPECT_EQ(write("sp", 1), ok);
    ASSERT_GT(disk_->fill(), 0u);
    // The image file's blocks exist: the save overwrites them in place.
    EXPECT_EQ(write("sp", 2), ok);
    EXPECT_EQ(next_value(), 2);
    // A reload that changes only the period keeps the value.
    reload_with(produced("sp", 10, capture_.port(), 30));
    EXPECT_EQ(next_value(), 2);
    EXPECT_EQ(write("sp", 3), ok);
    // A restart, on the disk still full, produces the last value answered ok from the first
    // datagram on.
    restart();
    EXPECT_NE(gateway_->output().find("bytes free"), std::string::npos) << gateway_->output();
    EXPECT_EQ(next_value(), 3);
    EXPECT_TRUE(recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        const auto m = json::parse(p);
        return m["image_save_failures"] == 0 && m["writes_ok"] == 0;
    }));
}

TEST_F(ImagePersistenceTest, AnExchangeWhoseImageCannotBeSavedRefusesWritesAndSaysWhy) {
    const auto port = free_tcp_port();
    start(produced("sp", 10, capture_.port()), "",
          {.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port) + "\n"});
    ASSERT_GT(disk_->fill(), 0u);
    // Added on a full disk: its file cannot be created.
    reload_with(produced("sp", 10, capture_.port()) + produced("added", 11, capture_.port()));
    const auto status = recorder_->wait_for_message(topic("added/_status"), [](const auto& p) {
        const auto s = json::parse(p);
        return s["saved"] == false && s["save_error"].is_string();
    });
    ASSERT_TRUE(status.has_value()) << gateway_->output();
    EXPECT_EQ(json::parse(status->payload)["save_error"],
              "write " + dir_.path() + "/state/added.image.tmp: No space left on device");
    const auto refused = write("added", 5);
    EXPECT_EQ(refused["ok"], false) << refused.dump();
    EXPECT_EQ(refused.value("error", "").rfind("not saved: ", 0), 0u) << refused.dump();
    EXPECT_NE(refused.value("error", "").find(dir_.path() + "/state/added.image.tmp"),
              std::string::npos)
        << refused.dump();
    EXPECT_EQ(next_value(11), 0);  // never produced
    EXPECT_TRUE(recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        const auto m = json::parse(p);
        return m["writes_not_saved"] == 1 && m["image_save_failures"] >= 1;
    }));
    std::string page;
    for (int i = 0; i < 100; ++i) {  // refreshed once a second
        page = http_get(port, "/metrics");
        if (page.find("eip2mqtt_writes_not_saved_total 1") != std::string::npos) break;
        std::this_thread::sleep_for(100ms);
    }
    EXPECT_NE(page.find("eip2mqtt_writes_not_saved_total 1"), std::string::npos) << page;
    EXPECT_NE(page.find(R"(eip2mqtt_exchange_image_saved{direction="produce",exchange="added"} 0)"),
              std::string::npos)
        << page;

    // Room again: the image is saved within a second or two, and writes are taken again.
    disk_->release();
    status_with("added", "saved", "true");
    EXPECT_EQ(write("added", 6), ok);
    EXPECT_EQ(next_value(11), 6);
}

TEST_F(ImagePersistenceTest, AWriteSentWhenItsSaveFailedIsAnsweredSavedFalse) {
    start(produced("sp", 10, capture_.port()));
    EXPECT_EQ(write("sp", 1), ok);
    // A careless hand: the file removed, a directory made in its place. The next save finds
    // its file gone and cannot put a new one there.
    const auto image = dir_.path() + "/state/sp.image";
    std::filesystem::remove(image);
    std::filesystem::create_directory(image);
    const auto unsaved = write("sp", 2);
    EXPECT_EQ(unsaved["ok"], true) << unsaved.dump();
    EXPECT_EQ(unsaved["saved"], false) << unsaved.dump();
    EXPECT_EQ(unsaved.value("error", ""), "not saved: rename " + image + ".tmp: Is a directory")
        << unsaved.dump();
    EXPECT_EQ(next_value(), 2);
    status_with("sp", "saved", "false");
    // From now on a write is saved before it is produced: this one is refused.
    const auto refused = write("sp", 3);
    EXPECT_EQ(refused["ok"], false) << refused.dump();
    EXPECT_EQ(next_value(), 2);
    EXPECT_TRUE(recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        const auto m = json::parse(p);
        return m["writes_sent_unsaved"] == 1 && m["writes_not_saved"] == 1;
    }));
    // Mended: the image in memory is saved within a second or two, and a restart produces it.
    const auto before_mending = recorder_->count();
    std::filesystem::remove(image);
    status_with("sp", "saved", "true", before_mending);
    restart();
    EXPECT_EQ(next_value(), 2);
}

TEST_F(ImagePersistenceTest, AReloadCarriesTheRunningImageOverWhateverTheFileHolds) {
    start(produced("sp", 10, capture_.port()));
    EXPECT_EQ(write("sp", 7), ok);
    std::filesystem::remove(dir_.path() + "/state/sp.image");
    const auto before_reload = recorder_->count();
    reload_with(produced("sp", 10, capture_.port(), 30));
    EXPECT_EQ(next_value(), 7);
    // ...and writes it back to the file.
    status_with("sp", "saved", "true", before_reload);
    restart();
    EXPECT_EQ(next_value(), 7);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
