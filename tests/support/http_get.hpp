#pragma once
/// A minimal HTTP client for tests of the Prometheus endpoint.

#include <cstdint>
#include <string>
#include <utility>

namespace eip2mqtt::test {

/// GET `path` over a plain HTTP/1.0 connection to 127.0.0.1:`port`; the whole response, or
/// an empty string when nothing answered within 5 s.
std::string http_get(std::uint16_t port, const std::string& path);
/// GET `path` and read the response until it holds `needle` (a stream that does not end: an
/// event stream), at most `timeout_ms`; what was read, whether or not it holds it.
std::string http_read_until(std::uint16_t port, const std::string& path, const std::string& needle,
                            int timeout_ms);
/// The same with another method (`HEAD`, `POST`...), and `headers` (whole lines, each ending in
/// CR LF) besides Host.
std::string http_request(std::uint16_t port, const std::string& method, const std::string& path,
                         const std::string& headers = "");
/// GET `path` over HTTPS to 127.0.0.1:`port` (`openssl s_client`, name localhost), trusting only
/// `ca_file`, with `headers` as above: whether the handshake verified and the whole response.
std::pair<bool, std::string> https_get(std::uint16_t port, const std::string& path,
                                       const std::string& ca_file, const std::string& headers = "");

/// The status line's code and the body of an HTTP response (`{"", response}` when it is none).
std::pair<std::string, std::string> status_and_body(const std::string& response);

/// A client that connects to 127.0.0.1:`port`, sends `sent` (nothing, or part of a request)
/// and then nothing more, until destroyed: what a slow or hostile client does to a server.
class SilentClient {
public:
    SilentClient(std::uint16_t port, const std::string& sent);
    ~SilentClient();
    SilentClient(const SilentClient&) = delete;
    SilentClient& operator=(const SilentClient&) = delete;

    bool connected() const { return connected_; }
    /// Waits up to `timeout_ms` for the server to close the connection; true when it did.
    bool closed_by_server(int timeout_ms) const;

private:
    int fd_ = -1;
    bool connected_ = false;
};

}  // namespace eip2mqtt::test
