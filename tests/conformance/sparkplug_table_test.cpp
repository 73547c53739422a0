// The conformance table of docs/sparkplug.md cannot drift: every tck-id of the specification
// (tests/data/sparkplug_tck_ids.txt) is judged by the suite or listed as not judged, never both,
// and the table says exactly that, row by row (on a mismatch the test prints the table it
// expects).

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "tests/conformance/sparkplug_requirements.hpp"

namespace eip2mqtt::test::conformance {
namespace EIP2MQTT_THIS_FILE {

std::vector<std::string> specification_ids() {
    std::ifstream in(std::string(EIP2MQTT_TEST_DATA) + "/sparkplug_tck_ids.txt");
    std::vector<std::string> ids;
    for (std::string line; std::getline(in, line);) {
        if (!line.empty() && line.front() != '#') ids.push_back(line);
    }
    return ids;
}

std::string status_of(const std::string& id) {
    for (const auto& r : edge_node_requirements()) {
        if (r.tck_id != id) continue;
        return r.run == Run::mqtt5 ? "judged: Mqtt5TheNodesWholeLifeHoldsEveryRequirement"
                                   : "judged: Mqtt311ACleanStopSaysTheNdeathBeforeItsDisconnect";
    }
    for (const auto& n : not_judged()) {
        if (n.tck_id == id) return "not judged: " + std::string(n.why);
    }
    return "missing";
}

/// The table as docs/sparkplug.md must hold it, between its markers.
std::string expected_table() {
    std::string table = "| tck-id | status |\n|---|---|\n";
    for (const auto& id : specification_ids()) {
        table += "| `" + id + "` | " + status_of(id) + " |\n";
    }
    return table;
}

std::string documented_table() {
    std::ifstream in(std::string(EIP2MQTT_DOCS_DIR) + "/sparkplug.md");
    std::stringstream text;
    text << in.rdbuf();
    const auto doc = text.str();
    const std::string begin = "<!-- conformance table: begin -->\n";
    const auto from = doc.find(begin);
    const auto to = doc.find("<!-- conformance table: end -->");
    if (from == std::string::npos || to == std::string::npos) return {};
    return doc.substr(from + begin.size(), to - from - begin.size());
}

TEST(SparkplugConformanceTable, EveryTckIdIsJudgedOrSaysWhyNotAndOnlyOnce) {
    const auto ids = specification_ids();
    ASSERT_GT(ids.size(), 250u);
    const std::set<std::string> known(ids.begin(), ids.end());
    EXPECT_EQ(known.size(), ids.size());
    std::map<std::string, int> seen;
    for (const auto& r : edge_node_requirements()) ++seen[std::string(r.tck_id)];
    for (const auto& n : not_judged()) ++seen[std::string(n.tck_id)];
    for (const auto& [id, count] : seen) {
        EXPECT_EQ(count, 1) << id << " is judged or listed more than once";
        EXPECT_TRUE(known.contains(id)) << id << " is not a tck-id of the specification";
    }
    for (const auto& id : ids)
        EXPECT_TRUE(seen.contains(id)) << id << " is neither judged nor listed";
}

TEST(SparkplugConformanceTable, TheDocsTableSaysWhatTheSuiteJudges) {
    const auto expected = expected_table();
    EXPECT_EQ(documented_table(), expected)
        << "docs/sparkplug.md's conformance table, between its markers, should read:\n"
        << expected;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test::conformance
