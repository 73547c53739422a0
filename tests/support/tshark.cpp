#include "tests/support/tshark.hpp"

#include <cctype>
#include <chrono>
#include <sstream>

#include "tests/support/child_process.hpp"

namespace eip2mqtt::test {
namespace {

constexpr char separator = '\x1f';  // a byte no decoded value contains

std::vector<std::string> tshark_argv(const std::string& plugin, const std::string& pcap) {
    std::vector<std::string> argv{"/usr/bin/tshark"};
    if (!plugin.empty()) {
        argv.push_back("-X");
        argv.push_back("lua_script:" + plugin);
    }
    argv.push_back("-r");
    argv.push_back(pcap);
    return argv;
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    for (const char c : line) {
        if (c == separator) {
            cells.push_back(cell);
            cell.clear();
        } else {
            cell += c;
        }
    }
    cells.push_back(cell);
    return cells;
}

}  // namespace

RunResult tshark_run(const std::string& plugin, const std::string& pcap,
                     const std::vector<std::string>& args) {
    auto argv = tshark_argv(plugin, pcap);
    argv.insert(argv.end(), args.begin(), args.end());
    ChildProcess tshark(argv, {{"TZ", "UTC"}});
    // CPU-bound: 100,000 datagrams with a plugin of 1,000 exchanges take 13 s on a quiet 2-core
    // machine and over 2 min with stress-ng loading both cores; the suite allows 300 s a test.
    const auto status = tshark.wait(std::chrono::seconds(270));
    return {status.value_or(-1), tshark.output()};
}

TsharkFields tshark_fields(const std::string& plugin, const std::string& pcap,
                           const std::vector<std::string>& fields,
                           const std::vector<std::string>& extra) {
    std::vector<std::string> args = extra;
    for (const auto* option :
         {"-T", "fields", "-E", "separator=\x1f", "-E", "occurrence=a", "-e", "frame.number"}) {
        args.emplace_back(option);
    }
    for (const auto& field : fields) {
        args.emplace_back("-e");
        args.push_back(field);
    }
    const auto run = tshark_run(plugin, pcap, args);
    TsharkFields result{run.status, run.output, {}};
    std::istringstream lines(run.output);
    for (std::string line; std::getline(lines, line);) {
        if (line.empty() || std::isdigit(static_cast<unsigned char>(line[0])) == 0) continue;
        auto cells = split(line);
        if (cells.size() == fields.size() + 1) result.rows.push_back(std::move(cells));
    }
    return result;
}

}  // namespace eip2mqtt::test
