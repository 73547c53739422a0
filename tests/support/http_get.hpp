#pragma once
/// A minimal HTTP client for tests of the Prometheus endpoint.

#include <cstdint>
#include <string>

namespace eip2mqtt::test {

/// GET `path` over a plain HTTP/1.0 connection to 127.0.0.1:`port`; the whole response, or
/// an empty string when nothing answered within 5 s.
std::string http_get(std::uint16_t port, const std::string& path);

}  // namespace eip2mqtt::test
