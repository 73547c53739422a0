#include "eip2mqtt/core/wire/header.hpp"

#include <gtest/gtest.h>

#include <unordered_map>

namespace eip2mqtt::core::wire {
namespace EIP2MQTT_THIS_FILE {

TEST(ProducerId, DottedFormIsHeldMostSignificantFirst) {
    EXPECT_EQ(parse_producer_id("172.23.21.176"), ProducerId{0xAC1715B0});
    EXPECT_EQ(parse_producer_id("192.168.1.1"), ProducerId{0xC0A80101});
    EXPECT_EQ(parse_producer_id("0.0.0.0"), ProducerId{0});
    EXPECT_EQ(parse_producer_id("255.255.255.255"), ProducerId{0xFFFFFFFF});
}

TEST(ProducerId, GeDecimalFormIsTheWireBytesReadLittleEndian) {
    // docs/protocol.md §2: 172.23.21.176 = 2954172332.
    EXPECT_EQ(parse_producer_id("2954172332"), ProducerId{0xAC1715B0});
    EXPECT_EQ(parse_producer_id("16885952"), ProducerId{0xC0A80101});
}

TEST(ProducerId, RejectsMalformedText) {
    for (const char* text : {"", "1.2.3", "1.2.3.4.5", "256.0.0.1", "1.2.3.", ".1.2.3", "a.b.c.d",
                             "1.2.3.-4", " 1.2.3.4", "-1", "4294967296", "1..2.3"}) {
        EXPECT_EQ(parse_producer_id(text), std::nullopt) << text;
    }
}

TEST(ProducerId, PrintsDotted) {
    EXPECT_EQ(to_string(ProducerId{0xAC1715B0}), "172.23.21.176");
    EXPECT_EQ(to_string(ProducerId{0x0A000005}), "10.0.0.5");
}

TEST(Signature, MajorIsByte25MinorIsByte24) {
    // V5: bytes 24..27 = 05 02 00 00, the field read little-endian is 0x0205.
    EXPECT_EQ(Signature::from_wire(0x0205), (Signature{2, 5}));
    EXPECT_EQ((Signature{2, 5}).to_wire(), 0x0205);
}

TEST(Signature, UpperSixteenBitsAreIgnored) {
    EXPECT_EQ(Signature::from_wire(0xFFFF0205), (Signature{2, 5}));
}

TEST(Signature, ZeroMeansNotUsed) {
    EXPECT_FALSE((Signature{0, 0}).is_set());
    EXPECT_TRUE((Signature{0, 1}).is_set());
    EXPECT_TRUE((Signature{1, 0}).is_set());
}

TEST(Signature, ParsesMajorDotMinorOrMajor) {
    EXPECT_EQ(parse_signature("2.5"), (Signature{2, 5}));
    EXPECT_EQ(parse_signature("3"), (Signature{3, 0}));
    EXPECT_EQ(parse_signature("255.255"), (Signature{255, 255}));
    for (const char* text : {"", "256", "2.256", "2.", ".5", "-2.5", "2.5.1", "x"}) {
        EXPECT_EQ(parse_signature(text), std::nullopt) << text;
    }
    EXPECT_EQ(to_string(Signature{2, 6}), "2.6");
}

TEST(Header, DefaultsToADataPduWithoutTimestamp) {
    Header header;
    EXPECT_EQ(header.pdu_type, 0x0D);
    EXPECT_EQ(header.pdu_version, 0x01);
    EXPECT_FALSE(header.has_timestamp());
    header.time_s = 1;
    EXPECT_TRUE(header.has_timestamp());
}

TEST(Header, KeyIsProducerIdAndExchangeId) {
    Header header;
    header.producer_id = ProducerId{0xC0A80101};
    header.exchange_id = 1;
    EXPECT_EQ(header.key(), (ExchangeKey{ProducerId{0xC0A80101}, 1}));
    EXPECT_NE(header.key(), (ExchangeKey{ProducerId{0xC0A80101}, 124}));
    EXPECT_NE(header.key(), (ExchangeKey{ProducerId{0xC0A80102}, 1}));
}

TEST(Header, ExchangeKeysWorkAsHashMapKeys) {
    std::unordered_map<ExchangeKey, int, ExchangeKeyHash> map;
    map[{ProducerId{1}, 2}] = 12;
    map[{ProducerId{2}, 1}] = 21;
    EXPECT_EQ(map.size(), 2u);
    EXPECT_EQ((map[{ProducerId{1}, 2}]), 12);
    EXPECT_EQ((map[{ProducerId{2}, 1}]), 21);
}

TEST(Header, ConstantsMatchTheSpec) {
    EXPECT_EQ(header_size, 32u);
    EXPECT_EQ(max_data_size, 1400u);
    EXPECT_EQ(max_datagram_size, 1432u);
    EXPECT_EQ(default_port, 18246);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::wire
