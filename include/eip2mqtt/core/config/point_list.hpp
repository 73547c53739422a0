#pragma once
/// SCADA point lists (docs/protocol.md §6): CSV with the columns TagName, Node, Address, DataType,
/// AccessType, and optionally Units, ScaleType, ScaleRawLow, ScaleRawHigh, ScaleEULow,
/// ScaleEUHigh and Clamp. The header row is required; columns may come in any order and their
/// names are case-insensitive; fields may be double-quoted, within their line (a quoted field
/// that runs onto the next line is an error); blank lines and lines starting with `#` are
/// skipped. Pure: the caller reads the file.

#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/config/diagnostic.hpp"
#include "eip2mqtt/core/plan/tag_plan.hpp"

namespace eip2mqtt::core::config {

struct PointRow {
    plan::TagSpec tag;  ///< name, address, type; writable when AccessType allows writes
    std::string node;   ///< the exchange it belongs to
    /// AccessType Write, W, ReadWrite, Read/Write, RW (produced) rather than Read or R (consumed).
    bool write = false;
    Mark mark;  ///< file and line of the row (column 1)
};

struct PointList {
    std::vector<PointRow> rows;
    Diagnostics errors;  ///< one per bad row or missing column; good rows are still returned
};

/// Parses CSV text; `file` names it in marks.
PointList parse_point_list(std::string_view text, const FileName& file);

}  // namespace eip2mqtt::core::config
