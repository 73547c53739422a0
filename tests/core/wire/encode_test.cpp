#include "eip2mqtt/core/wire/encode.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/core/vectors.hpp"

namespace eip2mqtt::core::wire {
namespace EIP2MQTT_THIS_FILE {

using test::from_hex;
using test::to_hex;
using test::utc_seconds;
namespace vectors = test::vectors;

std::string encoded(std::string_view hex) {
    const auto bytes = from_hex(hex);
    const auto datagram = decode_datagram(bytes);
    EXPECT_TRUE(datagram.ok());
    std::vector<std::byte> out(max_datagram_size, std::byte{0xEE});
    const std::size_t size = encode_datagram(datagram->header, datagram->data, out);
    EXPECT_EQ(size, bytes.size());
    out.resize(size);
    return to_hex(out);
}

TEST(Vectors, V1EncodesByteForByte) { EXPECT_EQ(encoded(vectors::v1), vectors::v1); }

TEST(Vectors, V2EncodesByteForByte) { EXPECT_EQ(encoded(vectors::v2), vectors::v2); }

TEST(Vectors, V3EncodesByteForByte) { EXPECT_EQ(encoded(vectors::v3), vectors::v3); }

TEST(Vectors, V4HeaderFieldsEncode) {
    Header header;
    header.request_id = 13969;
    header.producer_id = ProducerId{0xAC1715B0};
    header.exchange_id = 1;
    header.time_s = utc_seconds(2023, 2, 3, 16, 12, 35);
    header.time_ns = 260970100;
    std::array<std::byte, header_size> out{};
    encode_header(header, out);
    EXPECT_EQ(to_hex(std::span(out).first(20)), vectors::v4);
    EXPECT_EQ(to_hex(std::span(out).subspan(20)), "000000000000000000000000");
}

TEST(Vectors, V5HeaderWithSignatureEncodes) {
    Header header;
    header.request_id = 1;
    header.producer_id = *parse_producer_id("10.0.0.5");
    header.exchange_id = 7;
    header.signature = Signature{2, 5}.to_wire();
    std::array<std::byte, header_size> out{};
    encode_header(header, out);
    EXPECT_EQ(to_hex(out), vectors::v5);
}

TEST(ProducerRules, ProducerIdGoesOutInDottedOrder) {
    Header header;
    header.producer_id = *parse_producer_id("172.23.21.176");
    std::array<std::byte, header_size> out{};
    encode_header(header, out);
    EXPECT_EQ(to_hex(std::span(out).subspan(4, 4)), "ac1715b0");
}

TEST(ProducerRules, DatagramIsHeaderPlusExactlyTheData) {
    Header header;
    header.request_id = 0xFFFF;
    const std::vector<std::byte> data{std::byte{0x01}, std::byte{0x02}, std::byte{0x03}};
    std::vector<std::byte> out(40, std::byte{0xEE});
    EXPECT_EQ(encode_datagram(header, data, out), 35u);
    EXPECT_EQ(to_hex(out),
              "0d01ffff000000000000000000000000000000000000000000000000000000000102"
              "03eeeeeeeeee");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::wire
