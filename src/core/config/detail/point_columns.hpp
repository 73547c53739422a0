#pragma once
/// A point list's optional engineering columns (docs/configuration.md "Engineering values"):
/// Units, ScaleType, ScaleRawLow, ScaleRawHigh, ScaleEULow, ScaleEUHigh and Clamp, as SCADA
/// packages export a tag's scaling, and Count (an array's elements) and Length (a string's
/// bytes). Any may be left out of the header, and any field empty.
///
/// Module-private to src/core/config.

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "core/config/detail/csv_field.hpp"
#include "eip2mqtt/core/config/diagnostic.hpp"
#include "eip2mqtt/core/plan/tag_plan.hpp"

namespace eip2mqtt::core::config::detail {

class PointColumns {
public:
    /// Notes where the header row `fields` has each optional column.
    void find(const std::vector<CsvField>& fields);

    /// Reads a data row's optional fields into `tag`; false, with an error per bad field added
    /// to `errors`, when one does not read. `at` is the row's mark, whose column each field's
    /// replaces.
    bool read(const std::vector<CsvField>& fields, const Mark& at, plan::TagSpec& tag,
              Diagnostics& errors) const;

private:
    enum Column : std::size_t {
        units,
        type,
        raw_low,
        raw_high,
        eu_low,
        eu_high,
        clamp,
        elements,
        length,
        column_count
    };

    /// Count and Length into the tag's count; false when one is no count.
    bool read_count(const std::vector<CsvField>& fields, const Mark& at, plan::TagSpec& tag,
                    Diagnostics& errors) const;

    /// The field of `column` in `fields`; nullptr when the header lacks it or the row is short.
    const CsvField* field(const std::vector<CsvField>& fields, Column column) const;

    std::array<std::optional<std::size_t>, column_count> index_{};
};

}  // namespace eip2mqtt::core::config::detail
