#include "eip2mqtt/core/wire/decode.hpp"

#include <gtest/gtest.h>

#include <unordered_map>
#include <vector>

#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::wire {
namespace EIP2MQTT_THIS_FILE {

using test::from_hex;
using test::utc_seconds;
namespace vectors = test::vectors;

Result<Datagram, DropReason> decode(const std::vector<std::byte>& bytes) {
    return decode_datagram(bytes);
}

TEST(Vectors, V1DecodesHeader) {
    const auto bytes = from_hex(vectors::v1);
    const auto datagram = decode(bytes);
    ASSERT_TRUE(datagram.ok());
    const Header& h = datagram->header;
    EXPECT_EQ(h.pdu_type, 0x0D);
    EXPECT_EQ(h.pdu_version, 0x01);
    EXPECT_EQ(h.request_id, 108);
    EXPECT_EQ(to_string(h.producer_id), "192.168.1.1");
    EXPECT_EQ(h.exchange_id, 1u);
    EXPECT_EQ(h.time_s, utc_seconds(2023, 9, 20, 17, 41, 18));
    EXPECT_EQ(h.time_ns, 0u);
    EXPECT_EQ(h.status, 0u);
    EXPECT_EQ(h.signature, 0u);
    EXPECT_EQ(h.reserved, 0u);
    EXPECT_EQ(datagram->data.size(), 15u);
}

TEST(Vectors, V2DataViewsTheCallersBuffer) {
    const auto bytes = from_hex(vectors::v2);
    const auto datagram = decode(bytes);
    ASSERT_TRUE(datagram.ok());
    EXPECT_EQ(datagram->data.data(), bytes.data() + 32);
    EXPECT_EQ(datagram->data.size(), 15u);
    EXPECT_EQ(test::to_hex(datagram->data), "e75a0000b6804760960e0000000000");
}

TEST(Vectors, V3DecodesHeaderAndTimestamp) {
    const auto bytes = from_hex(vectors::v3);
    const auto datagram = decode(bytes);
    ASSERT_TRUE(datagram.ok());
    const Header& h = datagram->header;
    EXPECT_EQ(h.request_id, 20009);
    EXPECT_EQ(h.producer_id, ProducerId{0xC0A865D3});
    EXPECT_EQ(to_string(h.producer_id), "192.168.101.211");
    EXPECT_EQ(h.exchange_id, 3u);
    EXPECT_EQ(h.time_s, utc_seconds(2023, 8, 8, 22, 52, 10));
    EXPECT_EQ(h.time_ns, 567000680u);
    EXPECT_TRUE(h.has_timestamp());
    EXPECT_EQ(datagram->data.size(), 16u);
}

TEST(Vectors, V4HeaderFields) {
    auto bytes = from_hex(vectors::v4);
    ASSERT_EQ(bytes.size(), 20u);
    bytes.resize(32);  // the vector gives the first 20 bytes; the rest are zero
    const Header h = decode_header(bytes);
    EXPECT_EQ(h.pdu_type, 0x0D);
    EXPECT_EQ(h.pdu_version, 0x01);
    EXPECT_EQ(h.request_id, 13969);
    EXPECT_EQ(h.producer_id, ProducerId{0xAC1715B0});
    EXPECT_EQ(to_string(h.producer_id), "172.23.21.176");
    EXPECT_EQ(h.exchange_id, 1u);
    EXPECT_EQ(h.time_s, utc_seconds(2023, 2, 3, 16, 12, 35));
    EXPECT_EQ(h.time_ns, 260970100u);
}

TEST(Vectors, V5SignatureAndNoTimestamp) {
    const auto bytes = from_hex(vectors::v5);
    const Header h = decode_header(bytes);
    EXPECT_EQ(h.request_id, 1);
    EXPECT_EQ(to_string(h.producer_id), "10.0.0.5");
    EXPECT_EQ(h.exchange_id, 7u);
    EXPECT_EQ(h.time_s, 0u);
    EXPECT_EQ(h.time_ns, 0u);
    EXPECT_FALSE(h.has_timestamp());
    EXPECT_EQ(h.signature, 0x0205u);
    EXPECT_EQ(Signature::from_wire(h.signature), (Signature{2, 5}));
}

TEST(Vectors, V5HasNoDataAndIsDropped) {
    const auto result = decode(from_hex(vectors::v5));
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::no_data);
}

TEST(Vectors, V7ByteSwappedPduTypeIsNotADataPdu) {
    auto bytes = from_hex(vectors::v2);
    bytes[0] = std::byte{0x01};
    bytes[1] = std::byte{0x0D};
    const auto result = decode(bytes);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::not_data_pdu);
}

TEST(Vectors, V7CutTo31BytesIsTooShort) {
    auto bytes = from_hex(vectors::v2);
    bytes.resize(31);
    const auto result = decode(bytes);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::too_short);
}

TEST(Vectors, V7CutTo32BytesHasNoData) {
    auto bytes = from_hex(vectors::v2);
    bytes.resize(32);
    const auto result = decode(bytes);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::no_data);
}

TEST(Vectors, V7ExchangeId124IsNotTheConfiguredExchange) {
    // §4 rule 3 is a lookup by (producer id, exchange id); only exchange 1 is configured.
    auto bytes = from_hex(vectors::v2);
    bytes[8] = std::byte{124};
    const auto result = decode(bytes);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->header.exchange_id, 124u);
    const std::unordered_map<ExchangeKey, int, ExchangeKeyHash> configured{
        {ExchangeKey{ProducerId{0xC0A80101}, 1}, 0}};
    EXPECT_EQ(configured.count(result->header.key()), 0u);
    EXPECT_EQ(configured.count(decode(from_hex(vectors::v2))->header.key()), 1u);
}

TEST(Vectors, V7OneDataByteLessStillDecodes) {
    // The length check needs the configuration: see consumed_exchange_test.cpp.
    auto bytes = from_hex(vectors::v2);
    bytes.pop_back();
    const auto result = decode(bytes);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->data.size(), 14u);
}

TEST(ConsumerRules, Rule1EmptyDatagramIsTooShort) {
    const auto result = decode_datagram({});
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::too_short);
}

TEST(ConsumerRules, Rule1IsCheckedBeforeRule2) {
    const std::vector<std::byte> bytes(31, std::byte{0xFF});
    const auto result = decode(bytes);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::too_short);
}

TEST(ConsumerRules, Rule2WrongVersionIsNotADataPdu) {
    auto bytes = from_hex(vectors::v2);
    bytes[1] = std::byte{0x02};
    const auto result = decode(bytes);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::not_data_pdu);
}

TEST(ConsumerRules, Rule2CommandPduTypeIsNotADataPdu) {
    // §7: 0x0A is a command type on port 7937, not a data PDU.
    auto bytes = from_hex(vectors::v2);
    bytes[0] = std::byte{0x0A};
    const auto result = decode(bytes);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::not_data_pdu);
}

TEST(ConsumerRules, OneDataByteIsTheMinimum) {
    auto bytes = from_hex(vectors::v2);
    bytes.resize(33);
    const auto result = decode(bytes);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->data.size(), 1u);
}

TEST(ConsumerRules, FourteenHundredDataBytesIsTheMaximum) {
    auto bytes = from_hex(vectors::v2);
    bytes.resize(1432, std::byte{0x5A});
    const auto result = decode(bytes);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->data.size(), 1400u);
}

TEST(ConsumerRules, MoreThan1432BytesIsTooLong) {
    auto bytes = from_hex(vectors::v2);
    bytes.resize(1433);
    const auto result = decode(bytes);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error(), DropReason::too_long);
}

TEST(Header, StatusSignatureAndReservedAreRecordedNotRejected) {
    auto bytes = from_hex(vectors::v2);
    for (std::size_t i = 20; i < 32; ++i) bytes[i] = static_cast<std::byte>(i);
    const auto result = decode(bytes);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->header.status, 0x17161514u);
    EXPECT_EQ(result->header.signature, 0x1B1A1918u);
    EXPECT_EQ(result->header.reserved, 0x1F1E1D1Cu);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::wire
