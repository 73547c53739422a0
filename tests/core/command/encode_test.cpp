#include "eip2mqtt/core/command/encode.hpp"

#include <gtest/gtest.h>

#include <string>
#include <variant>

#include "eip2mqtt/core/command/command_status.hpp"
#include "eip2mqtt/core/command/decode.hpp"
#include "tests/core/command/command_vectors.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

using test::from_hex;
using test::to_hex;
namespace v = test::command_vectors;

wire::ProducerId producer(std::string_view dotted) {
    return wire::parse_producer_id(dotted).value();
}

std::string reencoded_request(std::string_view hex) {
    const auto decoded = decode_request(from_hex(hex));
    EXPECT_TRUE(decoded.ok()) << hex;
    if (!decoded) return {};
    return to_hex(
        std::visit([&](const auto& body) { return encode(decoded->header, body); }, decoded->body));
}

std::string reencoded_response(std::string_view hex) {
    const auto decoded = decode_response(from_hex(hex));
    EXPECT_TRUE(decoded.ok()) << hex;
    if (!decoded) return {};
    return to_hex(
        std::visit([&](const auto& body) { return encode(decoded->header, body); }, decoded->body));
}

TEST(CommandManualExample, RetrieveConfigurationResponseEncodesByteForByte) {
    PduHeader request;
    request.type = PduType::retrieve_config_request;
    request.request_id = 0x1111;
    ExchangeConfig config;
    config.key = {producer("105.102.0.200"), 0x2EE1};
    config.period_ms = 1600;
    config.destination_type = DestinationType::unicast;
    config.destination = producer("105.102.0.200").value;
    config.state = ExchangeState::active;
    config.length = 1400;
    config.mode = ExchangeMode::consumed;
    const auto pdu = encode(reply_header(request, PduType::retrieve_config_response), config);
    EXPECT_EQ(to_hex(pdu), v::c2_retrieve_config_response);
}

TEST(CommandManualExample, RetrieveConfigurationRequestEncodesByteForByte) {
    PduHeader header;
    header.request_id = 0x1111;
    const auto pdu = encode(header, RetrieveConfigRequest{{producer("105.102.0.200"), 0x2EE1}});
    EXPECT_EQ(to_hex(pdu), v::c1_retrieve_config_request);
}

TEST(CommandVectors, EveryRequestReencodesByteForByte) {
    for (const auto hex : {v::c1_retrieve_config_request, v::c3_capabilities_request,
                           v::c5_summary_request, v::c7_statistics_request, v::c9_read_request,
                           v::c11_write_request, v::c13_masked_write_request}) {
        EXPECT_EQ(reencoded_request(hex), hex);
    }
}

TEST(CommandVectors, EveryResponseReencodesByteForByte) {
    for (const auto hex :
         {v::c2_retrieve_config_response, v::c4_capabilities_response, v::c6_summary_response,
          v::c8_statistics_response, v::c10_read_response, v::c12_write_response, v::c15_nak}) {
        EXPECT_EQ(reencoded_response(hex), hex);
    }
}

TEST(CapabilitiesPdu, IdentificationIsCutToEightyCharactersAndEndsWithNul) {
    PduHeader header;
    Capabilities capabilities;
    capabilities.identification = std::string(200, 'x');
    const auto pdu = encode(header, capabilities);
    EXPECT_EQ(pdu.size(), 28u + 80u + 1u);
    EXPECT_EQ(pdu.back(), std::byte{0});
    const auto decoded = decode_response(pdu);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(std::get<Capabilities>(decoded->body).identification, std::string(80, 'x'));
}

TEST(SummaryPdu, AFullPageFitsIn1400Bytes) {
    SummaryPage page;
    page.total_cells = 300;
    page.cells.resize(max_summary_cells);
    const auto pdu = encode(PduHeader{}, page);
    EXPECT_LE(pdu.size(), max_pdu_size);
    EXPECT_GT(pdu.size() + summary_cell_size, max_pdu_size);
    const auto decoded = decode_response(pdu);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(std::get<SummaryPage>(decoded->body).cells.size(), max_summary_cells);
}

TEST(DataPdus, ReadResponseSizeCountsPadding) {
    std::vector<Cell> cells(2);
    cells[0].length = 3;
    cells[1].length = 8;
    EXPECT_EQ(read_response_size(cells), 32u + 4u + 4u + 4u + 8u);
}

TEST(DataPdus, ErrorResponsesAreTheFixedPartAlone) {
    PduHeader header;
    header.type = PduType::read_response;
    header.status = static_cast<std::uint8_t>(CommandStatus::unknown_exchange);
    DataPdu pdu;
    pdu.cells.push_back({0, 4, {std::byte{1}, std::byte{2}, std::byte{3}, std::byte{4}}, {}});
    EXPECT_EQ(encode(header, pdu).size(), data_fixed_size);
}

TEST(DataPdus, MaskedWriteRoundTripsWithOddLengths) {
    PduHeader header;
    header.type = PduType::masked_write_request;
    DataPdu pdu;
    pdu.key = {producer("10.1.2.3"), 99};
    pdu.cells.push_back({5,
                         3,
                         {std::byte{1}, std::byte{2}, std::byte{3}},
                         {std::byte{0xFF}, std::byte{0x0F}, std::byte{0x80}}});
    pdu.cells.push_back({9, 1, {std::byte{0x40}}, {std::byte{0x40}}});
    const auto bytes = encode(header, pdu);
    EXPECT_EQ(bytes.size(), 32u + (4 + 4 + 4) + (4 + 4 + 4));
    const auto decoded = decode_request(bytes);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(std::get<DataPdu>(decoded->body), pdu);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
