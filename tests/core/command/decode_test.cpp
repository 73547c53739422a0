#include "eip2mqtt/core/command/decode.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/core/command/command_vectors.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

using test::from_hex;
namespace v = test::command_vectors;

wire::ProducerId producer(std::string_view dotted) {
    return wire::parse_producer_id(dotted).value();
}

Result<Request, DecodeError> request(std::string_view hex) { return decode_request(from_hex(hex)); }

Result<Response, DecodeError> response(std::string_view hex) {
    return decode_response(from_hex(hex));
}

// Sets the length field (bytes 6-7) to the PDU's size after an edit.
std::vector<std::byte> with_length(std::vector<std::byte> pdu) {
    pdu[6] = static_cast<std::byte>(pdu.size() & 0xFF);
    pdu[7] = static_cast<std::byte>(pdu.size() >> 8);
    return pdu;
}

TEST(CommandManualExample, RetrieveConfigurationRequestDecodes) {
    const auto decoded = request(v::c1_retrieve_config_request);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(decoded->header.type, PduType::retrieve_config_request);
    EXPECT_EQ(decoded->header.request_id, 0x1111);
    EXPECT_EQ(decoded->header.length, 16);
    const auto& body = std::get<RetrieveConfigRequest>(decoded->body);
    EXPECT_EQ(body.key.producer_id, producer("105.102.0.200"));
    EXPECT_EQ(body.key.exchange_id, 0x2EE1u);
}

TEST(CommandManualExample, RetrieveConfigurationResponseDecodesEveryField) {
    const auto decoded = response(v::c2_retrieve_config_response);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(decoded->header.type, PduType::retrieve_config_response);
    EXPECT_EQ(decoded->header.request_id, 0x1111);
    EXPECT_EQ(decoded->header.status, 0);
    const auto& config = std::get<ExchangeConfig>(decoded->body);
    EXPECT_EQ(config.key.producer_id, producer("105.102.0.200"));
    EXPECT_EQ(config.key.exchange_id, 0x2EE1u);
    EXPECT_EQ(config.period_ms, 1600u);
    EXPECT_EQ(config.destination_type, DestinationType::unicast);
    EXPECT_EQ(config.destination, producer("105.102.0.200").value);
    EXPECT_EQ(config.state, ExchangeState::active);
    EXPECT_EQ(config.length, 1400);
    EXPECT_EQ(config.port, 18246);
    EXPECT_EQ(config.signature, 0);
    EXPECT_EQ(config.mode, ExchangeMode::consumed);
}

TEST(CommandHeaderChecks, FewerThanEightBytesHaveNoHeader) {
    EXPECT_EQ(request("0900050001").error(), DecodeError::no_header);
    EXPECT_EQ(decode_request({}).error(), DecodeError::no_header);
}

TEST(CommandHeaderChecks, MoreThan1400BytesAreOversized) {
    auto pdu = from_hex(v::c9_read_request);
    pdu.resize(1401);
    EXPECT_EQ(decode_request(with_length(pdu)).error(), DecodeError::oversized);
}

TEST(CommandHeaderChecks, VersionOtherThanOneIsRefused) {
    auto pdu = from_hex(v::c3_capabilities_request);
    pdu[4] = std::byte{2};
    EXPECT_EQ(decode_request(pdu).error(), DecodeError::wrong_version);
}

TEST(CommandHeaderChecks, LengthFieldMustBeTheDatagramSize) {
    auto pdu = from_hex(v::c7_statistics_request);
    pdu[6] = std::byte{0x11};
    EXPECT_EQ(decode_request(pdu).error(), DecodeError::wrong_length);
    pdu = from_hex(v::c7_statistics_request);
    pdu.pop_back();
    EXPECT_EQ(decode_request(pdu).error(), DecodeError::wrong_length);
}

TEST(CommandHeaderChecks, UnknownTypeIsRefused) {
    auto pdu = from_hex(v::c3_capabilities_request);
    pdu[0] = std::byte{0x0D};  // the data port's PDU type is not a command
    EXPECT_EQ(decode_request(pdu).error(), DecodeError::unknown_type);
}

TEST(CommandRequests, ResponsesAndNaksAreNotRequests) {
    EXPECT_EQ(request(v::c2_retrieve_config_response).error(), DecodeError::not_a_request);
    EXPECT_EQ(request(v::c15_nak).error(), DecodeError::not_a_request);
    EXPECT_EQ(response(v::c9_read_request).error(), DecodeError::not_a_response);
}

TEST(CommandRequests, EachFixedRequestDecodes) {
    const auto capabilities = request(v::c3_capabilities_request);
    ASSERT_TRUE(capabilities.ok());
    EXPECT_EQ(std::get<CapabilitiesRequest>(capabilities->body).producer_id, producer("10.0.0.5"));
    const auto summary = request(v::c5_summary_request);
    ASSERT_TRUE(summary.ok());
    EXPECT_EQ(std::get<SummaryRequest>(summary->body).index, 0);
    const auto statistics = request(v::c7_statistics_request);
    ASSERT_TRUE(statistics.ok());
    EXPECT_EQ(std::get<StatisticsRequest>(statistics->body).key.exchange_id, 7u);
}

TEST(CommandRequests, CapabilitiesRequestMayBeTheHeaderAlone) {
    const auto decoded = request("0900050001000800");
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(std::get<CapabilitiesRequest>(decoded->body).producer_id, wire::ProducerId{});
}

TEST(CommandRequests, FixedRequestsCutShortAreTruncatedAndLongerAreMalformed) {
    for (const auto hex :
         {v::c1_retrieve_config_request, v::c5_summary_request, v::c7_statistics_request}) {
        auto pdu = from_hex(hex);
        pdu.pop_back();
        EXPECT_EQ(decode_request(with_length(pdu)).error(), DecodeError::truncated) << hex;
        pdu = from_hex(hex);
        pdu.push_back(std::byte{0});
        EXPECT_EQ(decode_request(with_length(pdu)).error(), DecodeError::malformed) << hex;
    }
}

TEST(DataRequests, ReadRequestDecodesItsCells) {
    const auto decoded = request(v::c9_read_request);
    ASSERT_TRUE(decoded.ok());
    const auto& pdu = std::get<DataPdu>(decoded->body);
    EXPECT_EQ(pdu.key.producer_id, producer("10.0.0.5"));
    EXPECT_EQ(pdu.key.exchange_id, 7u);
    EXPECT_EQ(pdu.address_type, 0);
    ASSERT_EQ(pdu.cells.size(), 1u);
    EXPECT_EQ(pdu.cells[0].offset, 2);
    EXPECT_EQ(pdu.cells[0].length, 3);
    EXPECT_TRUE(pdu.cells[0].data.empty());
}

TEST(DataRequests, WriteAndMaskedWriteCarryDataAndMask) {
    const auto write = request(v::c11_write_request);
    ASSERT_TRUE(write.ok());
    const auto& cells = std::get<DataPdu>(write->body).cells;
    ASSERT_EQ(cells.size(), 1u);
    EXPECT_EQ(test::to_hex(cells[0].data), "e803");
    const auto masked = request(v::c13_masked_write_request);
    ASSERT_TRUE(masked.ok());
    const auto& cell = std::get<DataPdu>(masked->body).cells.at(0);
    EXPECT_EQ(test::to_hex(cell.data), "01");
    EXPECT_EQ(test::to_hex(cell.mask), "05");
}

TEST(DataRequests, NoCellEmptyCellOrOptionsAreMalformed) {
    EXPECT_EQ(request(v::c14_read_without_cells).error(), DecodeError::malformed);
    auto pdu = from_hex(v::c9_read_request);
    pdu[34] = pdu[35] = std::byte{0};  // a cell of length 0
    EXPECT_EQ(decode_request(pdu).error(), DecodeError::malformed);
    pdu = from_hex(v::c9_read_request);
    pdu[5] = std::byte{4};  // an option length
    EXPECT_EQ(decode_request(pdu).error(), DecodeError::malformed);
}

TEST(DataRequests, CellsPastTheEndAreTruncatedAndBytesAfterThemMalformed) {
    auto pdu = from_hex(v::c9_read_request);
    pdu[11] = std::byte{2};  // two cells announced, one sent
    EXPECT_EQ(decode_request(pdu).error(), DecodeError::truncated);
    pdu = from_hex(v::c11_write_request);
    pdu.resize(pdu.size() - 2);  // the data's padding cut
    EXPECT_EQ(decode_request(with_length(pdu)).error(), DecodeError::truncated);
    pdu = from_hex(v::c9_read_request);
    pdu.insert(pdu.end(), 4, std::byte{0});
    EXPECT_EQ(decode_request(with_length(pdu)).error(), DecodeError::malformed);
}

TEST(DataRequests, EveryPrefixOfEveryRequestFailsCleanly) {
    for (const auto hex : {v::c1_retrieve_config_request, v::c3_capabilities_request,
                           v::c5_summary_request, v::c7_statistics_request, v::c9_read_request,
                           v::c11_write_request, v::c13_masked_write_request}) {
        const auto full = from_hex(hex);
        for (std::size_t size = 0; size < full.size(); ++size) {
            std::vector<std::byte> prefix(full.begin(), full.begin() + size);
            if (size >= 8) prefix = with_length(prefix);
            const auto decoded = decode_request(prefix);
            // The header-only Capabilities request is the one valid prefix.
            if (hex == v::c3_capabilities_request && size == 8) continue;
            ASSERT_FALSE(decoded.ok()) << hex << " cut to " << size;
            EXPECT_EQ(decoded.error(), size < 8 ? DecodeError::no_header : DecodeError::truncated)
                << hex << " cut to " << size;
        }
    }
}

TEST(CommandResponses, EveryResponseTypeDecodes) {
    const auto capabilities = response(v::c4_capabilities_response);
    ASSERT_TRUE(capabilities.ok());
    EXPECT_EQ(std::get<Capabilities>(capabilities->body).identification, "eip2mqtt 0.1.0");
    const auto summary = response(v::c6_summary_response);
    ASSERT_TRUE(summary.ok());
    const auto& page = std::get<SummaryPage>(summary->body);
    EXPECT_EQ(page.total_cells, 2);
    ASSERT_EQ(page.cells.size(), 2u);
    EXPECT_EQ(page.cells[1].key.producer_id, producer("10.0.0.9"));
    EXPECT_EQ(page.cells[1].mode, ExchangeMode::consumed);
    EXPECT_EQ(page.cells[1].period_ms, 250u);
    const auto statistics = response(v::c8_statistics_response);
    ASSERT_TRUE(statistics.ok());
    EXPECT_EQ(std::get<ExchangeStatistics>(statistics->body).messages, 1234u);
    const auto read = response(v::c10_read_response);
    ASSERT_TRUE(read.ok());
    EXPECT_EQ(test::to_hex(std::get<DataPdu>(read->body).cells.at(0).data), "112233");
    EXPECT_TRUE(response(v::c12_write_response).ok());
    const auto nak = response(v::c15_nak);
    ASSERT_TRUE(nak.ok());
    EXPECT_EQ(std::get<CommandNak>(nak->body).error, "malformed");
    EXPECT_EQ(std::get<CommandNak>(nak->body).error_code, 6);
}

TEST(CommandResponses, SummaryAnnouncingMoreCellsThanSentIsTruncated) {
    auto pdu = from_hex(v::c6_summary_response);
    pdu[15] = std::byte{3};
    EXPECT_EQ(decode_response(pdu).error(), DecodeError::truncated);
}

TEST(CommandResponses, ReadResponseWithAnErrorStatusCarriesNoCell) {
    auto pdu = from_hex(v::c12_write_response);
    pdu[0] = std::byte{33};
    pdu[5] = std::byte{1};
    const auto decoded = decode_response(pdu);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(decoded->header.status, 1);
    EXPECT_TRUE(std::get<DataPdu>(decoded->body).cells.empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
