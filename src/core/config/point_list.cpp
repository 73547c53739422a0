#include "eip2mqtt/core/config/point_list.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>

#include "core/config/detail/csv_field.hpp"
#include "core/config/detail/point_columns.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::core::config {
namespace {

using Field = detail::CsvField;
using detail::equals_lower;

bool blank(char c) { return c == ' ' || c == '\t'; }

// A loop rather than find_first_not_of(" \t"): that one searches the set for every character,
// and this runs on every field of every row.
std::string_view trim(std::string_view text) {
    while (!text.empty() && blank(text.front())) text.remove_prefix(1);
    while (!text.empty() && blank(text.back())) text.remove_suffix(1);
    return text;
}

/// Splits one CSV line into `fields` (reused from line to line: a list of 100,000 rows would
/// otherwise allocate a string per field); fields may be double-quoted, with "" for a quote
/// inside. Returns false on a quote still open at the end of the line (a field spanning lines
/// is not supported), with `open_quote` its 1-based column.
bool split(std::string_view line, std::vector<Field>& fields, int& open_quote) {
    std::size_t count = 0;
    std::size_t i = 0;
    while (true) {
        if (fields.size() <= count) fields.emplace_back();
        Field& field = fields[count++];
        field.column = static_cast<int>(i) + 1;
        field.quoted = false;
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        if (i < line.size() && line[i] == '"') {
            open_quote = static_cast<int>(i) + 1;
            ++i;
            field.unquoted.clear();
            bool closed = false;
            while (i < line.size()) {
                if (line[i] == '"') {
                    if (i + 1 < line.size() && line[i + 1] == '"') {
                        field.unquoted += '"';
                        i += 2;
                        continue;
                    }
                    ++i;
                    closed = true;
                    break;
                }
                field.unquoted += line[i++];
            }
            if (!closed) return false;
            field.quoted = true;  // text is set below, once no emplace_back can move `unquoted`
            while (i < line.size() && line[i] != ',') ++i;  // tolerate spaces after the quote
        } else {
            const auto end = std::min(line.find(',', i), line.size());
            field.text = trim(line.substr(i, end - i));
            i = end;
        }
        if (i >= line.size()) break;
        ++i;  // the comma
    }
    fields.resize(count);
    // A short string lives inside its Field, so a view of it taken before a later emplace_back
    // reallocated the vector would dangle: point the quoted fields' views at their strings now.
    for (auto& field : fields) {
        if (field.quoted) field.text = field.unquoted;
    }
    return true;
}

/// How a record goes on past a line that ended inside a quoted field, read by split()'s rules
/// (a quote opens a field only at its start; "" inside quotes is a quote).
struct Continuation {
    std::size_t next = 0;  ///< where the next record starts
    int lines = 0;         ///< lines the record takes after its first
    int closed_at = 0;     ///< lines after the first where the quote closes; 0: never
};

/// Follows the record whose quoted field is open at the end of the line before `pos`.
Continuation follow_quote(std::string_view text, std::size_t pos) {
    Continuation out;
    out.next = text.size();
    if (pos >= text.size()) return out;
    out.lines = 1;
    bool inside = true;
    bool field_start = false;
    for (std::size_t i = pos; i < text.size(); ++i) {
        const char c = text[i];
        if (inside) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                ++i;
            } else if (c == '"') {
                inside = false;
                out.closed_at = out.lines;
            } else if (c == '\n' && i + 1 < text.size()) {
                ++out.lines;
            }
        } else if (c == '\n') {
            out.next = i + 1;
            return out;
        } else if (c == ',') {
            field_start = true;
        } else if (field_start && c == '"') {
            inside = true;
            field_start = false;
        } else if (c != ' ' && c != '\t') {
            field_start = false;
        }
    }
    if (inside) out.closed_at = 0;  // a later field opened a quote that never closes
    return out;
}

/// Whether an AccessType makes the tag writable; nullopt when it is none we know. Point lists
/// spell the same two kinds many ways; a tag the gateway may write is one it produces.
std::optional<bool> is_write_access(std::string_view access) {
    for (const std::string_view read : {"read", "r", "ro", "read only", "readonly"}) {
        if (equals_lower(access, read)) return false;
    }
    for (const std::string_view write :
         {"write", "w", "readwrite", "read/write", "read-write", "read write", "rw", "r/w"}) {
        if (equals_lower(access, write)) return true;
    }
    return std::nullopt;
}

constexpr std::array<std::string_view, 5> column_names{"tagname", "node", "address", "datatype",
                                                       "accesstype"};
enum Column : std::size_t { tag_name, node, address, data_type, access_type };

/// The required columns' places; the optional ones are PointColumns'.
struct ColumnIndex {
    std::array<std::size_t, column_names.size()> required{};
    detail::PointColumns optional;
};

/// Finds each column in the header row; returns the names of those it lacks, comma-separated.
std::string read_header(const std::vector<Field>& fields, ColumnIndex& index) {
    index.optional.find(fields);
    std::string missing;
    for (std::size_t c = 0; c < column_names.size(); ++c) {
        const auto it = std::find_if(fields.begin(), fields.end(), [&](const Field& f) {
            return equals_lower(f.text, column_names[c]);
        });
        if (it == fields.end()) {
            missing += (missing.empty() ? "" : ", ") + std::string(column_names[c]);
        } else {
            index.required[c] = static_cast<std::size_t>(it - fields.begin());
        }
    }
    return missing;
}

/// One data row; nullopt, with its errors added, when a field is bad.
std::optional<PointRow> read_row(const std::vector<Field>& fields, const ColumnIndex& index,
                                 const FileName& file, int line_number, Diagnostics& errors) {
    const auto field = [&](Column c) -> const Field& { return fields[index.required[c]]; };
    const auto at = [&](Column c) { return Mark{file, line_number, field(c).column}; };

    PointRow row;
    row.mark = Mark{file, line_number, 1};
    bool ok = true;
    row.tag.name = field(tag_name).text;
    if (row.tag.name.empty()) {
        errors.push_back({at(tag_name), "empty TagName"});
        ok = false;
    }
    row.node = field(node).text;
    if (row.node.empty()) {
        errors.push_back({at(node), "empty Node"});
        ok = false;
    }
    if (const auto parsed = plan::parse_address(field(address).text)) {
        row.tag.address = *parsed;
    } else {
        errors.push_back({at(address), "bad address " + in_quotes(field(address).text) +
                                           " (expected byte.bit)"});
        ok = false;
    }
    if (const auto type =
            plan::parse_tag_type(field(data_type).text, plan::TypeNaming::point_list)) {
        row.tag.type = *type;
    } else {
        std::string hint;
        if (const auto close = plan::tag_type_hint(field(data_type).text)) {
            hint = " (did you mean " + in_quotes(*close) + "?)";
        }
        errors.push_back(
            {at(data_type), "unknown DataType " + in_quotes(field(data_type).text) + hint +
                                " (expected Bit, Word, Real, Long or a "
                                "type of docs/protocol.md section 3, \"Data types\")"});
        ok = false;
    }
    const auto access = field(access_type).text;
    if (const auto write = is_write_access(access)) {
        row.write = *write;
        row.tag.writable = *write;
    } else {
        errors.push_back({at(access_type), "unknown AccessType " + in_quotes(access) +
                                               " (expected Read or R, or Write, W, ReadWrite, "
                                               "Read/Write or RW)"});
        ok = false;
    }
    ok = index.optional.read(fields, row.mark, row.tag, errors) && ok;
    if (!ok) return std::nullopt;
    return row;
}

/// The header row's columns; nullopt, with the error added, when it lacks one.
std::optional<ColumnIndex> header_of(const std::vector<Field>& fields, const Mark& at,
                                     Diagnostics& errors) {
    ColumnIndex index{};
    const auto missing = read_header(fields, index);
    if (missing.empty()) return index;
    errors.push_back({at, "point list header lacks column(s) " + missing +
                              " (expected TagName, Node, Address, DataType, AccessType)"});
    return std::nullopt;
}

/// Adds the data row of `fields` to `list`, or its errors.
void add_row(const std::vector<Field>& fields, const ColumnIndex& index, const FileName& file,
             int line_number, PointList& list) {
    const std::size_t needed = *std::max_element(index.required.begin(), index.required.end()) + 1;
    if (fields.size() < needed) {
        list.errors.push_back({Mark{file, line_number, 1},
                               "row has " + std::to_string(fields.size()) +
                                   " fields, expected at least " + std::to_string(needed)});
        return;
    }
    if (auto row = read_row(fields, index, file, line_number, list.errors)) {
        list.rows.push_back(std::move(*row));
    }
}

/// The lines of a point list, numbered from 1, without their line end (LF or CRLF), the first
/// without its byte order mark.
class Lines {
public:
    explicit Lines(std::string_view text) : text_(text) {}

    /// The next line; false after the last.
    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        auto end = text_.find('\n', pos_);
        if (end == std::string_view::npos) end = text_.size();
        line = text_.substr(pos_, end - pos_);
        pos_ = end + 1;
        ++number_;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        if (number_ == 1 && line.starts_with("\xEF\xBB\xBF")) line.remove_prefix(3);
        return true;
    }

    /// The number of the line next() gave last; 0 before the first.
    int number() const { return number_; }

    /// Skips the other lines of a record whose quoted field is still open at the end of the
    /// current line; returns the number of the line where the quote closes, 0 when none does.
    int skip_open_record() {
        const auto rest = follow_quote(text_, pos_);
        const int closed_at = rest.closed_at > 0 ? number_ + rest.closed_at : 0;
        pos_ = rest.next;
        number_ += rest.lines;
        return closed_at;
    }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    int number_ = 0;
};

/// A record goes on until its quote closes (CSV's rule): its other lines are not rows of their
/// own, which they would be reported as.
void skip_open_record(Lines& lines, const Mark& at, Diagnostics& errors) {
    if (const int closed_at = lines.skip_open_record(); closed_at > 0) {
        errors.push_back({at, "a quoted field runs past the end of the line, to line " +
                                  std::to_string(closed_at) +
                                  " (newlines inside fields are not supported)"});
    } else {
        errors.push_back(
            {at, "unterminated quoted field (no closing quote before the end of the file)"});
    }
}

}  // namespace

PointList parse_point_list(std::string_view text, const FileName& file) {
    PointList list;
    list.rows.reserve(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')));
    Lines lines(text);
    std::vector<Field> fields;
    std::optional<ColumnIndex> header;
    std::string_view line;
    while (lines.next(line)) {
        const auto trimmed = trim(line);
        if (trimmed.empty() || trimmed.front() == '#') continue;
        if (int open_quote = 1; !split(line, fields, open_quote)) {
            skip_open_record(lines, Mark{file, lines.number(), open_quote}, list.errors);
        } else if (header) {
            add_row(fields, *header, file, lines.number(), list);
        } else {
            header = header_of(fields, Mark{file, lines.number(), 1}, list.errors);
            if (!header) return list;
        }
    }
    if (!header) {
        const Mark at{file, lines.number() == 0 ? 1 : lines.number(), 1};
        list.errors.push_back({at, "point list is empty (no header row)"});
    }
    return list;
}

}  // namespace eip2mqtt::core::config
