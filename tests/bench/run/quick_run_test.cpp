// The benchmark driver (bench/run.py, what `bench/run.sh` runs) end to end in its short form:
// every scenario must run on this machine and put a measured figure in its row of
// the table. Whether a target is met is the benchmark's to say, never a test's: only that each
// row is there with a number. The regression guard (`--against`) runs too, against the build
// under test itself, so that nothing more is built: every row must carry the earlier build's
// figure and the ratio between the two, and every per-tag row its CPU per publication. Runs
// alone (RUN_SERIAL): it saturates both cores on purpose.

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

using Row = std::vector<std::string>;

/// The cells of a table line ("| a | b |"), or nothing for a line outside a table.
Row cells_of(const std::string& line) {
    if (line.rfind("| ", 0) != 0 || line.size() < 4 || line.substr(line.size() - 2) != " |") {
        return {};
    }
    Row cells;
    const std::string inner = line.substr(2, line.size() - 4);
    std::size_t from = 0;
    for (auto bar = inner.find(" | "); bar != std::string::npos; bar = inner.find(" | ", from)) {
        cells.push_back(inner.substr(from, bar - from));
        from = bar + 3;
    }
    cells.push_back(inner.substr(from));
    return cells;
}

/// The rows of the table whose header starts with `header_start` (header and rule excluded).
std::vector<Row> table_rows(const std::string& markdown, const std::string& header_start) {
    std::vector<Row> rows;
    bool inside = false;
    std::size_t at = 0;
    while (at < markdown.size()) {
        auto end = markdown.find('\n', at);
        if (end == std::string::npos) end = markdown.size();
        const std::string line = markdown.substr(at, end - at);
        at = end + 1;
        if (line.rfind(header_start, 0) == 0) {
            inside = true;
            continue;
        }
        auto cells = cells_of(line);
        if (cells.empty()) {
            if (inside && line.empty() && !rows.empty()) break;
            continue;
        }
        if (inside) rows.push_back(std::move(cells));
    }
    return rows;
}

const std::vector<std::string> brokers = {"tuned broker", "Debian's default broker"};

/// The per-tag rows of scenarios 2 and 3: one per QoS, exchange shape and broker setup; the
/// many small exchanges also split over two gateway processes (the tuning row).
std::vector<std::string> per_tag_figures() {
    std::vector<std::string> figures;
    for (const auto* qos : {"0", "1"}) {
        for (const auto* shape : {"1 x 100 tags", "100 x 10 tags"}) {
            for (const auto& broker : brokers) {
                for (const auto* changing : {"100 %", "10 %"}) {
                    const auto figure = std::string("tag publications/s, QoS ") + qos + ", " +
                                        changing + " changing, " + shape;
                    figures.push_back(figure + ", " + broker);
                    if (std::string(shape) == "100 x 10 tags") {
                        figures.push_back(figure + " as two gateways of 50 exchanges, " + broker);
                    }
                }
            }
        }
    }
    return figures;
}

const std::string overload_prefix = "overload tag publications/s";
const std::string peer_prefix =
    "Node-RED flow peer (udp in -> function -> mqtt out, MQTT 3.1.1): tag publications/s";
const std::string reference_load = "100 x 11 tags (ts lint + 10 dints), 6,000 datagrams/s";

/// Scenario 14: each build offered 5 x its own per-tag rate, by QoS, shape and broker; then the
/// reference load (100 x 11 tags at 6,000 datagrams/s), on the gateway and on the Node-RED flow
/// peer.
std::vector<std::string> overload_figures() {
    std::vector<std::string> figures;
    for (const auto* qos : {"0", "1"}) {
        for (const auto* shape : {"1 x 100 tags", "100 x 10 tags"}) {
            for (const auto& broker : brokers) {
                figures.push_back(overload_prefix + ", QoS " + qos + ", 100 % changing, " + shape +
                                  ", offered 5 x own rate, " + broker);
            }
        }
    }
    figures.push_back(overload_prefix + ", QoS 1, 100 % changing, " + reference_load +
                      " (the reference load), Debian's default broker");
    figures.push_back(peer_prefix + ", QoS 1, " + reference_load + ", Debian's default broker");
    return figures;
}

/// Scenario 15's rows (bytes on the wire) and 16's (the status page).
std::vector<std::string> wire_and_page_figures() {
    std::vector<std::string> figures;
    const std::string bytes = "MQTT bytes sent per tag update, ";
    const std::string aliased = bytes + "topic aliases, 1 x 100 tags on 5-level topics of 60 ";
    for (const auto* broker : {"tuned broker", "Debian's default broker"}) {
        figures.push_back(aliased + "characters, QoS 1, " + broker);  // 15
    }
    figures.push_back(bytes + "MQTT 5 (content type, format indicator)");  // 15
    const std::string watched = "status page, 10 event streams open against none: ";
    figures.push_back(watched + "datagrams/s accepted, zero loss");               // 16
    figures.push_back(watched + "tag publications/s");                            // 16
    figures.push_back("status page, time to first render in headless chromium");  // 16
    return figures;
}

/// One row per figure of the table (scenario in brackets), in bench/README.md's order.
std::vector<std::string> expected_figures() {
    std::vector<std::string> figures = {
        "datagrams/s accepted, zero loss",                                // 1
        "datagrams lost at 70 % of the bare recvmmsg ceiling, 100 x 10",  // 1
        // 1: the same load to the leading unit of a hot-standby pair (--quick: 1 s).
        "datagrams lost at 70 % of the bare recvmmsg ceiling, 100 x 10 tags, no tag changing, 1 s, "
        "a hot-standby pair configured",
    };
    for (const auto& figure : per_tag_figures()) figures.push_back(figure);  // 2, 3
    for (const auto* batch : {"1 x 100 tags", "100 x 10 tags", "100 x 10 tags, batch_first"}) {
        figures.push_back(std::string("tag updates/s carried in batch mode (_values), QoS 1, ") +
                          batch);  // 4
    }
    figures.push_back(  // 4: engineering values against the same tags unscaled
        "tag updates/s carried in batch mode (_values), every tag scaled (linear), QoS 1, "
        "100 x 10 tags");
    figures.push_back("tag updates/s carried by Sparkplug B DDATA, QoS 0");  // 4
    for (const auto* qos : {"0", "1"}) {
        for (const auto* shape : {"10 x 10 tags, 10,000 msgs/s", "100 x 10 tags, 4,000 msgs/s"}) {
            for (const auto& broker : brokers) {
                figures.push_back(std::string("latency datagram -> subscriber p99, QoS ") + qos +
                                  ", " + shape + ", " + broker);  // 5
            }
        }
    }
    for (const auto* figure : {
             "resident memory, 1,000 x 100 consumed + 100 produced",  // 6, inline YAML
             "start-up to READY, same configuration, inline YAML",    // 6
             "resident memory, 1,000 x 100 consumed + 100 produced",  // 6, point lists
             "start-up to READY, same configuration, point lists",    // 6
             "resident memory, 1,000 x 100 consumed + 100 produced",  // 6, status page on
             "start-up to READY, same configuration, point lists, status page on",          // 6
             "produced period, 100 x 10 ms: mean error",                                    // 7
             "produced period, 100 x 10 ms: p99 jitter",                                    // 7
             "produced period, 1000 x 10 ms: mean error",                                   // 7
             "produced period, 1000 x 10 ms: p99 jitter",                                   // 7
             "overload 5 x ceiling: RSS growth",                                            // 8
             "overload: newest value of each tag wins",                                     // 8
             "overload: datagrams accepted / sent",                                         // 8
             "overload: largest publish queue seen",                                        // 8
             "write latency /set -> datagram p99 (ms), 1 exchange",                         // 9
             "write latency /set -> datagram p99 (ms), 1 + 100",                            // 9
             "datagrams/s accepted, zero loss, journaling",                                 // 10
             "history replay rate",                                                         // 10
             "journal disk bytes per journaled tag update",                                 // 10
             "command requests/s answered, zero loss",                                      // 11
             "datagrams/s accepted, zero loss, command port flooded",                       // 11
             "s for tshark to decode",                                                      // 12
             "failover: SIGKILL of the leader -> first datagram of the new leader",         // 13
             "failover: SIGKILL of the leader -> first tag publication of the new leader",  // 13
         }) {
        figures.push_back(figure);
    }
    for (const auto& figure : overload_figures()) figures.push_back(figure);       // 14
    for (const auto& figure : wire_and_page_figures()) figures.push_back(figure);  // 15, 16
    figures.push_back(
        "broker move: SIGKILL of the broker in use -> `connected to` the next");  // 17
    return figures;
}

bool starts_with_digit(const std::string& cell) {
    return !cell.empty() && std::isdigit(static_cast<unsigned char>(cell[0]));
}

/// A row of the main table: the gateway's figure, and the earlier build's (here the same
/// build's) figure and the ratio of the two, all measured.
void expect_measured(const Row& row, const std::string& table) {
    ASSERT_EQ(row.size(), 8u) << row[0] << " in\n" << table;
    EXPECT_TRUE(starts_with_digit(row[1])) << row[0] << ": '" << row[1] << "'";
    if (row[0].rfind("tag publications/s", 0) == 0) {
        // Bare Paho is measured twice: alone (the target's baseline), and with the datagrams
        // the gateway was offered sent and received beside it.
        EXPECT_NE(row[2].find(" with the gateway's datagram input beside it"), std::string::npos)
            << row[0] << ": '" << row[2] << "'";
    }
    if (row[0].rfind(overload_prefix, 0) == 0) {
        // Against the earlier build, rate and CPU per publication: whether each is met.
        EXPECT_EQ(row[4], ">= 1.0 x self (and gateway CPU/publication <= self's)") << row[0];
        EXPECT_NE(row[5].find("; CPU/publication "), std::string::npos)
            << row[0] << ": '" << row[5] << "'";
    }
    if (row[0].rfind(peer_prefix, 0) == 0) {
        // Node-RED's own figure, and the gateway's ratio to it.
        EXPECT_TRUE(starts_with_digit(row[2])) << row[0] << ": '" << row[2] << "'";
        EXPECT_TRUE(starts_with_digit(row[3])) << row[0] << ": '" << row[3] << "'";
    }
    // The same binary runs every scenario: never "not in".
    EXPECT_TRUE(starts_with_digit(row[6])) << row[0] << ": '" << row[6] << "'";
    // A ratio, unless the earlier build's figure is 0 (nothing to divide by).
    const bool zero = std::strtod(row[6].c_str(), nullptr) == 0.0;
    EXPECT_TRUE(starts_with_digit(row[7]) || (zero && row[7].rfind("- (", 0) == 0))
        << row[0] << ": '" << row[7] << "'";
}

/// The runs of a row in the CPU table: this build, the earlier one, and the baseline of the
/// per-tag rows (bare Paho) or the peer's run (Node-RED); none for other rows.
std::vector<std::string> cpu_runs(const std::string& figure) {
    if (figure.rfind("tag publications/s", 0) == 0) return {"this build", "self", "bare Paho"};
    if (figure.rfind(overload_prefix, 0) == 0) return {"this build", "self"};
    if (figure.rfind(peer_prefix, 0) == 0) return {"this build", "self", "Node-RED"};
    return {};
}

/// The CPU table: each per-tag, overload and peer row, for each of its runs, with the
/// publications counted, the machine's CPU and the gateway's (or publisher's, or peer's) per
/// publication; in the overload rows, the gateway's thread by thread.
void expect_cpu_rows(const std::vector<Row>& rows, const std::vector<Row>& main_rows,
                     const std::string& markdown) {
    std::vector<std::pair<std::string, std::string>> expected;
    for (const auto& row : main_rows) {
        for (const auto& run : cpu_runs(row[0])) expected.emplace_back(row[0], run);
    }
    ASSERT_EQ(rows.size(), expected.size()) << markdown;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& row = rows[i];
        ASSERT_EQ(row.size(), 8u) << markdown;
        EXPECT_EQ(row[0], expected[i].first);
        EXPECT_EQ(row[1], expected[i].second);
        for (std::size_t cell = 2; cell <= 4; ++cell) {
            EXPECT_TRUE(starts_with_digit(row[cell]))
                << row[0] << ", " << row[1] << ": '" << row[cell] << "'";
        }
        if (row[0].rfind(overload_prefix, 0) == 0 && row[4].rfind("0.0 us", 0) != 0) {
            // Thread by thread: the gateway's threads that ran, by name (a gateway that got no
            // CPU in a short run on a loaded machine has none to name).
            EXPECT_NE(row[4].find(" us ("), std::string::npos) << row[0] << ": '" << row[4] << "'";
        }
    }
}

TEST(BenchRun, EveryScenarioOfTheQuickRunFillsItsRowsWithMeasuredFigures) {
    TempDir results;
    const std::string gateway = std::string(EIP2MQTT_BUILD_DIR) + "/eip2mqtt";
    const auto run = run_command(
        {"/usr/bin/env", "PYTHONDONTWRITEBYTECODE=1", "EIP2MQTT_BENCH_BUILD=" EIP2MQTT_BUILD_DIR,
         "EIP2MQTT_BENCH_RESULTS=" + results.path(), "python3",
         std::string(EIP2MQTT_SOURCE_DIR) + "/bench/run.py", "--quick", "--against-binary", gateway,
         "--against-label", "self"},
        1400s);
    ASSERT_EQ(run.status, 0) << run.output;
    std::ifstream in(results.path() + "/quick.md");
    const std::string markdown{std::istreambuf_iterator<char>(in), {}};

    // The machine is named by its CPU and by bare Paho's rate in this run.
    EXPECT_NE(markdown.find("\n- machine: "), std::string::npos) << markdown;
    EXPECT_NE(markdown.find("\n- bare Paho on this machine, this run: QoS 0 "), std::string::npos)
        << markdown;
    EXPECT_NE(markdown.find("\n- against: self "), std::string::npos) << markdown;
    // And the build by the commit of its source tree.
    const auto gateway_line = markdown.find("\n- gateway: ");
    ASSERT_NE(gateway_line, std::string::npos) << markdown;
    const auto line =
        markdown.substr(gateway_line, markdown.find('\n', gateway_line + 1) - gateway_line);
    EXPECT_NE(line.find(", source "), std::string::npos) << line;

    const auto rows = table_rows(markdown, "| figure | gateway |");
    const auto figures = expected_figures();
    ASSERT_EQ(rows.size(), figures.size()) << markdown << run.output;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        EXPECT_EQ(rows[i][0].rfind(figures[i], 0), 0u) << rows[i][0];
        expect_measured(rows[i], markdown);
    }
    expect_cpu_rows(table_rows(markdown, "| figure | run |"), rows, markdown);
}

}  // namespace
}  // namespace eip2mqtt::test
