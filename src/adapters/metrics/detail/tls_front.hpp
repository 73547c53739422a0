#pragma once
/// HTTPS for the metrics listener (metrics.tls): civetweb as Debian 12 builds it crashes on the
/// first TLS connection (OpenSSL 3, docs/decisions/0007), so civetweb listens on loopback alone
/// and this front, on the configured address, speaks TLS with the configured certificate and
/// relays each connection's bytes to it, both ways. Boost.Asio's SSL streams over OpenSSL, on a
/// thread of its own: a slow browser never holds the gateway's loop.

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>

namespace eip2mqtt::adapters::metrics::detail {

class TlsFront {
public:
    /// Connections relayed at once; one beyond is closed as it comes (the listener's own
    /// worker bound is lower still: detail::server_threads).
    static constexpr int max_connections = 64;
    /// A client has this long to finish its handshake.
    static constexpr int handshake_timeout_ms = 5000;

    /// Listens on `listen` (host:port; port 0 picks a free one) with the certificate chain
    /// `cert` and key `key` (PEM), relaying to 127.0.0.1:`inner_port`. Throws
    /// std::runtime_error saying what failed: a file, the key not the certificate's, the
    /// address.
    TlsFront(const std::string& listen, const std::string& cert, const std::string& key,
             std::uint16_t inner_port);
    /// Stops listening and closes every connection.
    ~TlsFront();
    TlsFront(const TlsFront&) = delete;
    TlsFront& operator=(const TlsFront&) = delete;

    std::uint16_t port() const { return port_; }

private:
    void accept();

    boost::asio::io_context io_;
    boost::asio::ssl::context tls_;
    boost::asio::ip::tcp::acceptor acceptor_;
    boost::asio::ip::tcp::endpoint inner_;
    std::uint16_t port_ = 0;
    std::shared_ptr<int> open_;  ///< its use count: connections being relayed, plus one
    std::thread thread_;
};

}  // namespace eip2mqtt::adapters::metrics::detail
