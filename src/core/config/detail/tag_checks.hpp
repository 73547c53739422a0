#pragma once
/// The checks of each tag of an exchange (tag_checks.cpp): its name and topic, its address
/// against its type and the exchange's length, and its values against its type's range. The
/// Validator holds one, whose buffers serve one exchange after the other.
///
/// Module-private to src/core/config.

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::core::config::detail {

class TagChecks {
public:
    /// Adds the problems of `exchange`'s tags to `out`, in file order. `topic_bytes`: the
    /// length of the exchange's topic, whose tags' topics are checked for length; 0: they are
    /// not.
    void run(const ExchangeConfig& exchange, std::size_t topic_bytes, Diagnostics& out);

private:
    void error(const Mark& mark, std::string message) {
        out_->push_back({mark, std::move(message)});
    }
    /// Fills first_with_name_: for each tag of `exchange`, the index of the first tag with the
    /// same (valid) name, or -1. Sorting views of the names costs less than a hash-map node per
    /// tag (a configuration may hold 100,000 tags).
    void find_repeated_names(const ExchangeConfig& exchange);
    void check_values(const ExchangeConfig& exchange, const TagConfig& tag);
    /// min, max and initial against the type's range (a scaled tag's against its scale's).
    void check_limits(const TagConfig& tag, const std::function<std::string()>& what);

    Diagnostics* out_ = nullptr;                                     ///< during run()
    std::vector<std::pair<std::string_view, std::size_t>> by_name_;  ///< find_repeated_names
    std::vector<int> first_with_name_;
};

}  // namespace eip2mqtt::core::config::detail
