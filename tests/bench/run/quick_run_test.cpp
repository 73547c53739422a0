// The benchmark driver (bench/run.py, what `bench/run.sh` runs) end to end in its short form:
// every scenario of issue #6 must run on this machine and put a measured figure in its row of
// the table. Whether a target is met is the benchmark's to say, never a test's: only that each
// row is there with a number. Runs alone (RUN_SERIAL): it saturates both cores on purpose.

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

/// The table's rows: the cells of each line starting with "| ", header and rule excluded.
std::vector<std::vector<std::string>> table_rows(const std::string& markdown) {
    std::vector<std::vector<std::string>> rows;
    std::size_t at = 0;
    while (at < markdown.size()) {
        auto end = markdown.find('\n', at);
        if (end == std::string::npos) end = markdown.size();
        const std::string line = markdown.substr(at, end - at);
        at = end + 1;
        if (line.rfind("| ", 0) != 0 || line.rfind("| figure ", 0) == 0) continue;
        std::vector<std::string> cells;
        std::size_t from = 2;
        for (auto bar = line.find(" | ", from); bar != std::string::npos;
             bar = line.find(" | ", from)) {
            cells.push_back(line.substr(from, bar - from));
            from = bar + 3;
        }
        rows.push_back(std::move(cells));
    }
    return rows;
}

TEST(BenchRun, EveryScenarioOfTheQuickRunFillsItsRowsWithMeasuredFigures) {
    TempDir results;
    const auto run = run_command(
        {"/usr/bin/env", "PYTHONDONTWRITEBYTECODE=1", "EIP2MQTT_BENCH_BUILD=" EIP2MQTT_BUILD_DIR,
         "EIP2MQTT_BENCH_RESULTS=" + results.path(), "python3",
         std::string(EIP2MQTT_SOURCE_DIR) + "/bench/run.py", "--quick"},
        900s);
    ASSERT_EQ(run.status, 0) << run.output;
    std::ifstream in(results.path() + "/quick.md");
    const std::string table{std::istreambuf_iterator<char>(in), {}};
    const auto rows = table_rows(table);

    // One row per figure of the table (scenario in brackets), in bench/README.md's order.
    // Scenarios 2, 3 and 5 have a row per QoS, exchange shape and broker setup (issue #17); the
    // many small exchanges of 2 and 3 also split over two gateway processes (the tuning row).
    const std::vector<std::string> brokers = {"tuned broker", "Debian's default broker"};
    std::vector<std::string> figures = {"datagrams/s accepted, zero loss"};  // 1
    for (const auto* qos : {"0", "1"}) {
        for (const auto* shape : {"1 x 100 tags", "100 x 10 tags"}) {
            for (const auto& broker : brokers) {
                for (const auto* changing : {"100 %", "10 %"}) {  // 2, 3
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
    for (const auto* batch : {"1 x 100 tags", "100 x 10 tags", "100 x 10 tags, batch_first"}) {
        figures.push_back(std::string("tag updates/s carried in batch mode (_values), QoS 1, ") +
                          batch);  // 4
    }
    for (const auto* qos : {"0", "1"}) {
        figures.push_back(std::string("tag updates/s carried by Sparkplug B DDATA, QoS ") +
                          qos);  // 4
    }
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
             "produced period, 100 x 10 ms: mean error",              // 7
             "produced period, 100 x 10 ms: p99 jitter",              // 7
             "produced period, 1000 x 10 ms: mean error",             // 7
             "produced period, 1000 x 10 ms: p99 jitter",             // 7
             "overload 5 x ceiling: RSS growth",                      // 8
             "overload: newest value of each tag wins",               // 8
             "overload: datagrams accepted / sent",                   // 8
             "overload: largest publish queue seen",                  // 8
             "write latency /set -> datagram p99 (ms), 1 exchange",   // 9
             "write latency /set -> datagram p99 (ms), 1 + 100",      // 9
             "datagrams/s accepted, zero loss, journaling",           // 10
             "history replay rate",                                   // 10
             "journal disk bytes per journaled tag update",           // 10
         }) {
        figures.push_back(figure);
    }
    ASSERT_EQ(rows.size(), figures.size()) << table << run.output;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& row = rows[i];
        ASSERT_EQ(row.size(), 5u) << "row " << i << " of\n" << table;  // the last cell ends in " |"
        EXPECT_EQ(row[0].rfind(figures[i], 0), 0u) << row[0];
        // The gateway's figure is a measurement: it starts with a digit.
        EXPECT_TRUE(!row[1].empty() && std::isdigit(static_cast<unsigned char>(row[1][0])))
            << row[0] << ": '" << row[1] << "'";
        if (row[0].rfind("tag publications/s", 0) == 0) {
            // Bare Paho is measured twice: alone (the target's baseline), and with the datagrams
            // the gateway was offered sent and received beside it.
            EXPECT_NE(row[2].find(" with the gateway's datagram input beside it"),
                      std::string::npos)
                << row[0] << ": '" << row[2] << "'";
        }
    }
}

}  // namespace
}  // namespace eip2mqtt::test
