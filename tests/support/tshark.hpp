#pragma once
/// Runs tshark on a capture, with a Lua plugin when given, and reads its `-T fields` output.

#include <string>
#include <vector>

#include "tests/support/child_process.hpp"

namespace eip2mqtt::test {

struct TsharkFields {
    int status = -1;
    std::string output;  ///< everything tshark wrote, for failure messages
    /// One row per frame: frame.number, then the fields asked for ("" when absent).
    std::vector<std::vector<std::string>> rows;
};

/// `tshark [-X lua_script:PLUGIN] -r PCAP [extra...] -T fields -e frame.number -e FIELD...` in
/// UTC, bounded to two minutes. Rows are the output lines that start with a frame number.
TsharkFields tshark_fields(const std::string& plugin, const std::string& pcap,
                           const std::vector<std::string>& fields,
                           const std::vector<std::string>& extra = {});

/// tshark's status and output (standard output and error) of
/// `tshark [-X lua_script:PLUGIN] -r PCAP args...` in UTC, bounded to two minutes.
RunResult tshark_run(const std::string& plugin, const std::string& pcap,
                     const std::vector<std::string>& args);

}  // namespace eip2mqtt::test
