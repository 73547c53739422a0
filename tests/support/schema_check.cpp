#include "tests/support/schema_check.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {

std::string schema_file(const std::string& name) {
    return std::string(EIP2MQTT_DOCS_DIR) + "/schema/" + name;
}

std::string schema_problem(const std::string& schema_path, const std::string& json_text) {
    return schema_problems({{schema_path, json_text}}).front();
}

std::vector<std::string> schema_problems(const std::vector<SchemaCheck>& checks) {
    std::vector<std::string> problems(checks.size());
    if (checks.empty()) return problems;
    // Records "SCHEMA<TAB>LENGTH\n" + payload: payloads may hold any byte, newlines included.
    TempDir dir;
    std::ostringstream records;
    for (const auto& check : checks) {
        records << check.schema_path << '\t' << check.json_text.size() << '\n' << check.json_text;
    }
    const auto input = dir.write("payloads", records.str());
    const auto result = run_command({EIP2MQTT_PYTHON3, EIP2MQTT_SCHEMA_VALIDATOR, "--batch", input},
                                    std::chrono::seconds(60));
    if (result.status != 0) {
        for (auto& problem : problems) {
            problem = "the schema validator failed (status " + std::to_string(result.status) +
                      "): " + result.output;
        }
        return problems;
    }
    // One line per invalid payload, "INDEX<TAB>PROBLEM"; anything else (a warning Python
    // wrote on stderr) is no verdict.
    std::istringstream lines(result.output);
    for (std::string line; std::getline(lines, line);) {
        const auto tab = line.find('\t');
        if (tab == 0 || tab == std::string::npos || line.find_first_not_of("0123456789") != tab) {
            continue;
        }
        const auto index = std::strtoul(line.c_str(), nullptr, 10);
        if (index < checks.size()) problems[index] = line.substr(tab + 1);
    }
    return problems;
}

}  // namespace eip2mqtt::test
