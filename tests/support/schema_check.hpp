#pragma once
/// Checks JSON payloads against the JSON Schemas of docs/schema, with Debian's python3-jsonschema
/// run on tests/support/validate_schema.py, so that the documented schemas and the gateway's real
/// output cannot drift apart.

#include <string>
#include <vector>

namespace eip2mqtt::test {

/// The path of a schema of docs/schema: schema_file("tag-value.json").
std::string schema_file(const std::string& name);

/// The validator's message for `json_text` against the schema at `schema_path`; empty when the
/// text is JSON that the schema accepts. Problems of the validator itself (no python3, no
/// jsonschema, a schema that is not valid against its metaschema) are problems too.
std::string schema_problem(const std::string& schema_path, const std::string& json_text);

struct SchemaCheck {
    std::string schema_path;
    std::string json_text;
};

/// schema_problem of each check, in order, in one run of the validator (starting Python and
/// importing jsonschema costs more than validating a few hundred payloads).
std::vector<std::string> schema_problems(const std::vector<SchemaCheck>& checks);

}  // namespace eip2mqtt::test
