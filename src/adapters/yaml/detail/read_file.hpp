#pragma once
/// Reading a configuration or a point list: only a regular file, of at most max_file_bytes,
/// never blocking (a FIFO) and never growing without end (/dev/zero).
///
/// Module-private to src/adapters/yaml.

#include <string>

#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::adapters::yaml::detail {

/// The whole of a regular file of at most max_file_bytes, or why not, with `what` naming it
/// ("point list 'x.csv'"). Opened without blocking (a FIFO without a writer would block the
/// open for ever), checked on the opened descriptor (what is read is what was checked), and
/// never read past the limit, whatever its size said (a file may grow meanwhile; /proc files
/// say 0). Read as a stream, a directory ended in std::bad_alloc, a FIFO blocked and
/// /dev/zero grew the memory without end.
core::Result<std::string, std::string> read_file(const std::string& path, const std::string& what);

}  // namespace eip2mqtt::adapters::yaml::detail
