#pragma once
/// The command-protocol vectors of docs/protocol.md §9.6, as hex of UDP payloads.

#include <string_view>

namespace eip2mqtt::test::command_vectors {

/// C1: the manual's worked example, Retrieve Configuration request (as its hex dump has it:
/// exchange 0x2EE1 of producer 105.102.0.200; its table misprints the exchange as 0x2EE0).
inline constexpr std::string_view c1_retrieve_config_request = "0300111101001000696600c8e12e0000";

/// C2: the manual's worked example, the module's 76-byte Retrieve Configuration response.
inline constexpr std::string_view c2_retrieve_config_response =
    "0400111101004c00696600c8e12e00004006000000000100696600c8"
    "00000000000000000000000000000000000000000000000000000000"
    "0200780500000000464700000000020000000000";

/// C3, C4: Capabilities request of producer 10.0.0.5, and eip2mqtt's response.
inline constexpr std::string_view c3_capabilities_request = "0900050001000c000a000005";
inline constexpr std::string_view c4_capabilities_response =
    "0a00050001002b000a00000500000000040000000700000000000000"
    "656970326d71747420302e312e3000";

/// C5, C6: Summary from index 0, and a page of two cells.
inline constexpr std::string_view c5_summary_request = "0700060001000c0000000000";
inline constexpr std::string_view c6_summary_response =
    "0800060001003100000a00000502000200"
    "0a000005070000000100020064000000"
    "0a0000090300000002000100fa000000";

/// C7, C8: Statistics of 10.0.0.5 / 7, and the response.
inline constexpr std::string_view c7_statistics_request = "0f000700010010000a00000507000000";
inline constexpr std::string_view c8_statistics_response =
    "10000700010030000a0000050700000000f15365280000000200000008000000"
    "d2040000000000000000000000000000";

/// C9, C10: Read of 3 bytes at offset 2, and the response (data padded to 4 bytes).
inline constexpr std::string_view c9_read_request =
    "2000080001002400000000010a0000050700000000000000000000000000000002000300";
inline constexpr std::string_view c10_read_response =
    "2100080001002800000000010a0000050700000000f153650000000000000000"
    "0200030011223300";

/// C11, C12: Write of 1000 as a word at offset 4, and the response (the fixed part alone).
inline constexpr std::string_view c11_write_request =
    "2200090001002800000000010a000005070000000000000000000000000000000400"
    "0200e8030000";
inline constexpr std::string_view c12_write_response =
    "2300090001002000000000000a0000050700000000f153650000000000000000";

/// C13: Masked Write of byte 0: data 0x01, mask 0x05 (bit 0 set, bit 2 cleared).
inline constexpr std::string_view c13_masked_write_request =
    "24000a0001002c00000000010a00000507000000000000000000000000000000"
    "000001000100000005000000";

/// C14, C15: a Read request with no cell, and the NAK it gets (malformed).
inline constexpr std::string_view c14_read_without_cells =
    "20000b0001002000000000000a00000507000000000000000000000000000000";
inline constexpr std::string_view c15_nak =
    "12000b0001002e000a0000050700000006000000"
    "20000b0001002000000000000a000005"
    "6d616c666f726d656400";

/// C16: the challenge to C5 from a requester that has not proved its address, token 0xABCDEF.
inline constexpr std::string_view c16_challenge = "0800060001090c00efcdab00";

}  // namespace eip2mqtt::test::command_vectors
