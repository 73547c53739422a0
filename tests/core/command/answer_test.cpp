#include "eip2mqtt/core/command/answer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eip2mqtt/core/command/encode.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

using test::to_hex;

wire::ProducerId producer(std::string_view dotted) {
    return wire::parse_producer_id(dotted).value();
}

plan::TagSpec tag(std::string name, std::uint16_t byte, plan::TagType type, bool writable,
                  std::uint8_t bit = 0) {
    plan::TagSpec spec;
    spec.name = std::move(name);
    spec.address = {byte, bit};
    spec.type = type;
    spec.writable = writable;
    return spec;
}

plan::ExchangePlan make_plan(std::string name, std::string_view id, std::uint32_t exchange,
                             plan::Direction direction, std::uint16_t length, int period_ms,
                             std::vector<plan::TagSpec> tags) {
    plan::ExchangeSpec spec;
    spec.name = name;
    spec.direction = direction;
    spec.producer_id = producer(id);
    spec.exchange_id = exchange;
    spec.length = length;
    spec.period = std::chrono::milliseconds(period_ms);
    spec.topic = name;
    spec.tags = std::move(tags);
    return plan::make_exchange_plan(spec, "base");
}

// A produced exchange of 8 bytes (bits 0.0 and 0.2 writable, 0.1 read-only, a read-only byte
// at 1, a writable word at 4 with max 4000) and a consumed one of 4 bytes.
class Answers : public ::testing::Test {
protected:
    Answers() {
        auto speed = tag("SPEED", 4, plan::TagType::word, true);
        speed.mutable_extras().max = 4000;
        produced_ = make_plan("out", "10.0.0.5", 7, plan::Direction::produce, 8, 100,
                              {tag("RUN", 0, plan::TagType::bit, true, 0),
                               tag("FAULT", 0, plan::TagType::bit, false, 1),
                               tag("RESET", 0, plan::TagType::bit, true, 2),
                               tag("MODE", 1, plan::TagType::byte, false), speed});
        consumed_ = make_plan("in", "10.0.0.9", 3, plan::Direction::consume, 4, 250, {});
        image_ = test::from_hex("0500aa00e8030000");
        views_.resize(2);
        views_[0] = {&produced_, ExchangeMode::produced, ExchangeState::active};
        views_[0].image = image_;
        views_[0].time_s = 1700000000;
        views_[0].writable = true;
        views_[0].messages = 1234;
        views_[1] = {&consumed_, ExchangeMode::consumed, ExchangeState::idle};
        node_.producer_id = producer("10.0.0.5");
        node_.identification = "eip2mqtt 0.1.0";
    }

    Answer ask(PduType type, RequestBody body) {
        Request request{PduHeader{type, 0, 42}, std::move(body)};
        return answer(request, node_, views_);
    }

    Response response(PduType type, RequestBody body) {
        const auto answered = ask(type, std::move(body));
        const auto* bytes = std::get_if<std::vector<std::byte>>(&answered);
        EXPECT_NE(bytes, nullptr);
        if (bytes == nullptr) return {};
        auto decoded = decode_response(*bytes);
        EXPECT_TRUE(decoded.ok());
        EXPECT_EQ(decoded->header.request_id, 42);
        return std::move(decoded).value();
    }

    static DataPdu cells(wire::ExchangeKey key, std::vector<Cell> list) {
        DataPdu pdu;
        pdu.key = key;
        pdu.cells = std::move(list);
        return pdu;
    }

    CommandStatus status_of(PduType type, DataPdu pdu) {
        return static_cast<CommandStatus>(response(type, std::move(pdu)).header.status);
    }

    StageWrites staged(PduType type, DataPdu pdu) {
        auto answered = ask(type, std::move(pdu));
        EXPECT_TRUE(std::holds_alternative<StageWrites>(answered));
        return std::holds_alternative<StageWrites>(answered) ? std::get<StageWrites>(answered)
                                                             : StageWrites{};
    }

    plan::ExchangePlan produced_;
    plan::ExchangePlan consumed_;
    std::vector<std::byte> image_;
    std::vector<ExchangeView> views_;
    NodeInfo node_;
    const wire::ExchangeKey out_{producer("10.0.0.5"), 7};
    const wire::ExchangeKey in_{producer("10.0.0.9"), 3};
};

std::vector<std::byte> bytes(std::string_view hex) { return test::from_hex(hex); }

TEST_F(Answers, RetrieveConfigurationDescribesTheExchange) {
    const auto r = response(PduType::retrieve_config_request, RetrieveConfigRequest{in_});
    EXPECT_EQ(r.header.type, PduType::retrieve_config_response);
    EXPECT_EQ(r.header.status, 0);
    const auto& config = std::get<ExchangeConfig>(r.body);
    EXPECT_EQ(config.key, in_);
    EXPECT_EQ(config.period_ms, 250u);
    EXPECT_EQ(config.length, 4);
    EXPECT_EQ(config.mode, ExchangeMode::consumed);
    EXPECT_EQ(config.state, ExchangeState::idle);
}

TEST_F(Answers, UnknownExchangeGetsTheFullResponseWithAStatus) {
    const wire::ExchangeKey unknown{producer("10.0.0.5"), 99};
    const auto answered = ask(PduType::retrieve_config_request, RetrieveConfigRequest{unknown});
    ASSERT_EQ(std::get<std::vector<std::byte>>(answered).size(), config_response_size);
    const auto r = decode_response(std::get<std::vector<std::byte>>(answered)).value();
    EXPECT_EQ(r.header.status, static_cast<std::uint8_t>(CommandStatus::unknown_exchange));
    EXPECT_EQ(std::get<ExchangeConfig>(r.body).key, unknown);
    const auto s = response(PduType::statistics_request, StatisticsRequest{unknown});
    EXPECT_EQ(s.header.status, static_cast<std::uint8_t>(CommandStatus::unknown_exchange));
}

TEST_F(Answers, SummaryListsEveryExchangeFromTheIndex) {
    const auto all =
        std::get<SummaryPage>(response(PduType::summary_request, SummaryRequest{0}).body);
    EXPECT_EQ(all.total_cells, 2);
    ASSERT_EQ(all.cells.size(), 2u);
    EXPECT_EQ(all.cells[0].key, out_);
    EXPECT_EQ(all.cells[0].mode, ExchangeMode::produced);
    EXPECT_EQ(all.cells[1].period_ms, 250u);
    const auto rest =
        std::get<SummaryPage>(response(PduType::summary_request, SummaryRequest{1}).body);
    ASSERT_EQ(rest.cells.size(), 1u);
    EXPECT_EQ(rest.cells[0].key, in_);
    EXPECT_TRUE(std::get<SummaryPage>(response(PduType::summary_request, SummaryRequest{9}).body)
                    .cells.empty());
}

TEST_F(Answers, SummaryPagesHoldAtMost86Cells) {
    std::vector<plan::ExchangePlan> plans;
    for (std::uint32_t i = 0; i < 100; ++i) {
        plans.push_back(make_plan("e" + std::to_string(i), "10.0.0.5", 100 + i,
                                  plan::Direction::consume, 4, 100, {}));
    }
    views_.clear();
    for (const auto& p : plans) views_.push_back({&p, ExchangeMode::consumed});
    const auto first =
        std::get<SummaryPage>(response(PduType::summary_request, SummaryRequest{0}).body);
    EXPECT_EQ(first.total_cells, 100);
    EXPECT_EQ(first.cells.size(), 86u);
    const auto second =
        std::get<SummaryPage>(response(PduType::summary_request, SummaryRequest{86}).body);
    ASSERT_EQ(second.cells.size(), 14u);
    EXPECT_EQ(second.cells[0].key.exchange_id, 186u);
}

TEST_F(Answers, CapabilitiesIdentifyTheNodeAndWhatItDoes) {
    auto caps =
        std::get<Capabilities>(response(PduType::capabilities_request, CapabilitiesRequest{}).body);
    EXPECT_EQ(caps.identification, "eip2mqtt 0.1.0");
    EXPECT_EQ(caps.producer_id, producer("10.0.0.5"));
    EXPECT_EQ(caps.capabilities, capability::produces | capability::consumes | capability::read);
    node_.writes = true;
    caps =
        std::get<Capabilities>(response(PduType::capabilities_request, CapabilitiesRequest{}).body);
    EXPECT_NE(caps.capabilities & capability::write, 0u);
    EXPECT_NE(caps.capabilities & capability::masked_write, 0u);
}

TEST_F(Answers, StatisticsCarryTheViewsCounters) {
    const auto stats = std::get<ExchangeStatistics>(
        response(PduType::statistics_request, StatisticsRequest{out_}).body);
    EXPECT_EQ(stats.messages, 1234u);
    EXPECT_EQ(stats.length, 8u);
    EXPECT_EQ(stats.state, ExchangeState::active);
}

TEST_F(Answers, ReadReturnsTheImageBytesAndTheirTime) {
    const auto r = response(PduType::read_request, cells(out_, {{4, 2}, {0, 1}}));
    EXPECT_EQ(r.header.type, PduType::read_response);
    const auto& pdu = std::get<DataPdu>(r.body);
    EXPECT_EQ(pdu.time_s, 1700000000u);
    ASSERT_EQ(pdu.cells.size(), 2u);
    EXPECT_EQ(to_hex(pdu.cells[0].data), "e803");
    EXPECT_EQ(to_hex(pdu.cells[1].data), "05");
}

TEST_F(Answers, ReadRefusalsCarryTheirStatus) {
    EXPECT_EQ(status_of(PduType::read_request, cells(in_, {{0, 1}})), CommandStatus::no_data);
    EXPECT_EQ(status_of(PduType::read_request, cells(out_, {{7, 2}})), CommandStatus::out_of_range);
    auto pdu = cells(out_, {{0, 1}});
    pdu.signature = 0x0102;
    EXPECT_EQ(status_of(PduType::read_request, pdu), CommandStatus::signature_mismatch);
    pdu = cells(out_, {{0, 1}});
    pdu.address_type = 1;
    EXPECT_EQ(status_of(PduType::read_request, pdu), CommandStatus::unsupported_address);
    // 200 cells of 8 bytes: a response of 32 + 200 x 12 bytes, over 1400.
    EXPECT_EQ(status_of(PduType::read_request, cells(out_, std::vector<Cell>(200, Cell{0, 8}))),
              CommandStatus::out_of_range);
}

TEST_F(Answers, WritesAreRefusedWhenOffOrToAConsumedExchange) {
    const auto write = cells(out_, {{4, 2, bytes("d007")}});
    EXPECT_EQ(status_of(PduType::write_request, write), CommandStatus::not_permitted);
    node_.writes = true;
    EXPECT_EQ(status_of(PduType::write_request, cells(in_, {{0, 1, bytes("01")}})),
              CommandStatus::not_permitted);
}

TEST_F(Answers, AWriteToAWritableWordIsStagedWithItsValue) {
    node_.writes = true;
    const auto stage = staged(PduType::write_request, cells(out_, {{4, 2, bytes("d007")}}));
    EXPECT_EQ(stage.exchange, &produced_);
    ASSERT_EQ(stage.writes.size(), 1u);
    EXPECT_EQ(produced_.tags[stage.writes[0].tag_index].spec.name, "SPEED");
    EXPECT_EQ(std::get<std::uint64_t>(stage.writes[0].value), 2000u);
}

TEST_F(Answers, WriteChecksAreThoseOfAnMqttWrite) {
    node_.writes = true;
    // 5000 is over the tag's max of 4000: refused by the write checks, with their reason, for
    // the write handler to count and answer as an MQTT write's.
    const auto refused = staged(PduType::write_request, cells(out_, {{4, 2, bytes("8813")}}));
    EXPECT_TRUE(refused.writes.empty());
    ASSERT_TRUE(refused.rejection.has_value());
    EXPECT_EQ(refused.rejection->error, write::WriteError::above_max);
    // Byte 1 is a read-only tag; byte 6 is no tag at all; bits of byte 0 include read-only 0.1.
    EXPECT_EQ(status_of(PduType::write_request, cells(out_, {{1, 1, bytes("01")}})),
              CommandStatus::not_permitted);
    EXPECT_EQ(status_of(PduType::write_request, cells(out_, {{6, 1, bytes("01")}})),
              CommandStatus::not_permitted);
    EXPECT_EQ(status_of(PduType::write_request, cells(out_, {{0, 1, bytes("01")}})),
              CommandStatus::not_permitted);
    EXPECT_EQ(status_of(PduType::write_request, cells(out_, {{7, 2, bytes("0101")}})),
              CommandStatus::out_of_range);
}

TEST_F(Answers, AMaskedWriteChangesOnlyTheMaskedBits) {
    node_.writes = true;
    // The image has bits 0 and 2 of byte 0 set (0x05): set bit 0, clear bit 2.
    const auto stage =
        staged(PduType::masked_write_request, cells(out_, {{0, 1, bytes("01"), bytes("05")}}));
    ASSERT_EQ(stage.writes.size(), 2u);
    EXPECT_EQ(produced_.tags[stage.writes[0].tag_index].spec.name, "RUN");
    EXPECT_EQ(std::get<bool>(stage.writes[0].value), true);
    EXPECT_EQ(produced_.tags[stage.writes[1].tag_index].spec.name, "RESET");
    EXPECT_EQ(std::get<bool>(stage.writes[1].value), false);
    // The read-only bit 0.1 in the mask: refused.
    EXPECT_EQ(
        status_of(PduType::masked_write_request, cells(out_, {{0, 1, bytes("02"), bytes("02")}})),
        CommandStatus::not_permitted);
    // A mask of zeros writes nothing, and says so at once.
    EXPECT_EQ(
        status_of(PduType::masked_write_request, cells(out_, {{0, 1, bytes("ff"), bytes("00")}})),
        CommandStatus::success);
}

TEST_F(Answers, WriteResponseEchoesTheExchange) {
    Request request{PduHeader{PduType::masked_write_request, 3, 77},
                    cells(out_, {{0, 1, bytes("01"), bytes("01")}})};
    const auto r = decode_response(write_response(request, CommandStatus::failed, 5, 6)).value();
    EXPECT_EQ(r.header.type, PduType::masked_write_response);
    EXPECT_EQ(r.header.flag, 3);
    EXPECT_EQ(r.header.request_id, 77);
    EXPECT_EQ(r.header.status, static_cast<std::uint8_t>(CommandStatus::failed));
    EXPECT_EQ(std::get<DataPdu>(r.body).key, out_);
    EXPECT_EQ(std::get<DataPdu>(r.body).time_s, 5u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
