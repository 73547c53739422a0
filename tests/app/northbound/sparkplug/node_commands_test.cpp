// What hosts send, read by NodeCommands alone: NCMD rebirth by name, typed or not, the primary
// host's STATE (stale ones ignored, only changes told), and a DCMD handed on as one
// WriteRequest naming the node as its origin.

#include "eip2mqtt/app/northbound/sparkplug/node_commands.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/app/support/sparkplug_node_fixture.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using adapters::sparkplug::DataType;
using core::plan::Direction;
using core::plan::Value;
using test::by_name;
using test::command;
using test::sparkplug_plan;
using test::untyped_command;
using Asked = NodeCommands::Asked;

class NodeCommandsTest : public ::testing::Test, public WriteHandler, public Northbound {
protected:
    NodeCommandsTest() {
        devices_.exchanges_changed({{&in_}, {&out_}});
        session_.tick(core::MonoTime{} + std::chrono::hours(24));
    }
    void on_write(WriteRequest&& request) override { writes_.push_back(std::move(request)); }

    static adapters::mqtt::Incoming message(std::string topic, std::string payload) {
        adapters::mqtt::Incoming in;
        in.topic = std::move(topic);
        in.payload = std::move(payload);
        return in;
    }
    Asked state(bool online, std::int64_t timestamp) {
        return commands_.on_message(
            message("spBv1.0/STATE/scada", std::string(R"({"online":)") +
                                               (online ? "true" : "false") + R"(,"timestamp":)" +
                                               std::to_string(timestamp) + "}"),
            devices_, session_);
    }
    /// Connected and born, the host online.
    void born() {
        session_.connected();
        session_.set_host_online(true);
        ASSERT_TRUE(session_.begin_birth(false));
        session_.set_born();
    }

    core::plan::ExchangePlan in_ = sparkplug_plan("in", Direction::consume);
    core::plan::ExchangePlan out_ = sparkplug_plan("out", Direction::produce);
    DeviceRegistry devices_{"plant1", "gw1"};
    NodeSession session_{"spBv1.0/plant1/NDEATH/gw1", true};
    NodeCommands commands_{"plant1", "gw1", "scada", *this, *this};
    std::vector<WriteRequest> writes_;
};

TEST_F(NodeCommandsTest, SubscribesToNcmdEveryDcmdAndTheHostsState) {
    EXPECT_EQ(commands_.subscriptions(),
              (std::vector<std::string>{"spBv1.0/plant1/NCMD/gw1", "spBv1.0/plant1/DCMD/gw1/+",
                                        "spBv1.0/STATE/scada"}));
    NodeCommands hostless("plant1", "gw1", "", *this, *this);
    EXPECT_EQ(hostless.subscriptions().size(), 2u);
    EXPECT_EQ(hostless.on_message(message("spBv1.0/STATE/", "{}"), devices_, session_),
              Asked::nothing);
}

TEST_F(NodeCommandsTest, AnNcmdRebirthByNameWithOrWithoutItsDatatypeAsksARebirth) {
    const auto ncmd = [&](std::string payload) {
        return commands_.on_message(message("spBv1.0/plant1/NCMD/gw1", std::move(payload)),
                                    devices_, session_);
    };
    EXPECT_EQ(ncmd(command({by_name("Node Control/Rebirth", DataType::boolean, Value{true})})),
              Asked::rebirth);
    EXPECT_EQ(
        ncmd(untyped_command({by_name("Node Control/Rebirth", DataType::boolean, Value{true})})),
        Asked::rebirth);
    // The metric has no alias (Sparkplug B 3.0): alias 1 is no rebirth, nor a value of another
    // kind than boolean.
    EXPECT_EQ(ncmd(command({{"", 1, 0, DataType::boolean, Value{true}, false, {}}})),
              Asked::nothing);
    EXPECT_EQ(ncmd(untyped_command(
                  {by_name("Node Control/Rebirth", DataType::int32, Value{std::int64_t{1}})})),
              Asked::nothing);
    EXPECT_EQ(ncmd(command({by_name("Node Control/Rebirth", DataType::boolean, Value{false})})),
              Asked::nothing);
    EXPECT_EQ(ncmd("not protobuf \xff"), Asked::nothing);
    EXPECT_TRUE(writes_.empty());
}

TEST_F(NodeCommandsTest, TheHostsStateIsToldWhenItChangesAndAStaleOneIsIgnored) {
    session_.connected();
    EXPECT_EQ(state(true, 100), Asked::host_online);
    session_.set_host_online(true);
    EXPECT_EQ(state(true, 200), Asked::nothing);   // no change
    EXPECT_EQ(state(false, 150), Asked::nothing);  // older than the last one taken
    EXPECT_EQ(state(false, 300), Asked::host_offline);
    session_.set_host_online(false);
    EXPECT_EQ(commands_.on_message(message("spBv1.0/STATE/scada", R"({"online":true})"), devices_,
                                   session_),
              Asked::nothing);
    // A new connection takes the host's retained STATE again, whatever its timestamp.
    commands_.connected();
    EXPECT_EQ(state(true, 50), Asked::host_online);
}

TEST_F(NodeCommandsTest, ADcmdIsOneWriteRequestFromTheNodeOrARefusal) {
    const auto dcmd = [&](std::string device) {
        const auto alias = devices_.find(&out_)->alias_base + 1;
        commands_.on_message(
            message("spBv1.0/plant1/DCMD/gw1/" + device,
                    command({by_name("A", DataType::int32, Value{std::int64_t{5}}),
                             {"", alias, 0, DataType::float32, Value{2.5f}, false, {}}})),
            devices_, session_);
    };
    dcmd("out");  // not born
    born();
    dcmd("out");
    dcmd("in");
    dcmd("nowhere");
    ASSERT_EQ(writes_.size(), 4u);
    for (const auto& request : writes_) {
        EXPECT_EQ(request.reply.origin, static_cast<Northbound*>(this));
        EXPECT_EQ(request.reply.via, WriteOrigin::sparkplug);
    }
    const auto error = [&](std::size_t i) {
        return std::get<core::write::WriteRejection>(writes_[i].outcome).error;
    };
    EXPECT_EQ(error(0), core::write::WriteError::offline);
    const auto& write = std::get<ExchangeWrite>(writes_[1].outcome);
    EXPECT_EQ(write.producer, &out_);
    ASSERT_EQ(write.writes.size(), 2u);
    EXPECT_EQ(write.writes[0].tag_index, 0u);
    EXPECT_EQ(write.writes[1].tag_index, 1u);
    EXPECT_EQ(error(2), core::write::WriteError::read_only);
    EXPECT_EQ(error(3), core::write::WriteError::unknown_tag);
}

TEST_F(NodeCommandsTest, ADcmdWithoutDatatypesTakesEachTagsOwn) {
    born();
    const auto alias = devices_.find(&out_)->alias_base;
    const auto dcmd = [&](const adapters::sparkplug::Metric& metric) {
        commands_.on_message(message("spBv1.0/plant1/DCMD/gw1/out", untyped_command({metric})),
                             devices_, session_);
    };
    // By alias alone, as a host that uses aliases sends it: A is a dint (Int32), B a real.
    dcmd({"", alias, 0, DataType::int32, Value{std::int64_t{-7}}, false, {}});
    dcmd({"", alias + 1, 0, DataType::float32, Value{2.5f}, false, {}});
    // A value of another kind than the tag's datatype says is refused, not converted.
    dcmd({"", alias, 0, DataType::float32, Value{2.5f}, false, {}});
    ASSERT_EQ(writes_.size(), 3u);
    const auto& a = std::get<ExchangeWrite>(writes_[0].outcome);
    ASSERT_EQ(a.writes.size(), 1u);
    EXPECT_EQ(a.writes[0].tag_index, 0u);
    EXPECT_EQ(a.writes[0].value, (Value{std::int64_t{-7}}));
    const auto& b = std::get<ExchangeWrite>(writes_[1].outcome);
    ASSERT_EQ(b.writes.size(), 1u);
    EXPECT_EQ(b.writes[0].tag_index, 1u);
    EXPECT_EQ(std::get<core::write::WriteRejection>(writes_[2].outcome).error,
              core::write::WriteError::wrong_type);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
