#include "adapters/metrics/detail/tls_front.hpp"

#include <array>
#include <boost/asio/connect.hpp>
#include <boost/asio/ssl/stream.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/write.hpp>
#include <boost/system/system_error.hpp>
#include <chrono>
#include <stdexcept>
#include <utility>

namespace eip2mqtt::adapters::metrics::detail {
namespace {

namespace asio = boost::asio;
using asio::ip::tcp;

/// One client's connection and its twin to civetweb, relayed until either side ends.
class Relay : public std::enable_shared_from_this<Relay> {
public:
    Relay(asio::ssl::stream<tcp::socket> client, std::shared_ptr<int> count)
        : client_(std::move(client)),
          inner_(client_.get_executor()),
          timer_(client_.get_executor()),
          count_(std::move(count)) {}

    void start(const tcp::endpoint& inner) {
        timer_.expires_after(std::chrono::milliseconds(TlsFront::handshake_timeout_ms));
        timer_.async_wait([self = shared_from_this()](boost::system::error_code ec) {
            if (!ec) self->close();
        });
        client_.async_handshake(asio::ssl::stream_base::server,
                                [self = shared_from_this(), inner](boost::system::error_code ec) {
                                    if (ec) return self->close();
                                    self->timer_.cancel();
                                    self->connect(inner);
                                });
    }

private:
    void connect(const tcp::endpoint& inner) {
        inner_.async_connect(inner, [self = shared_from_this()](boost::system::error_code ec) {
            if (ec) return self->close();
            self->pump(self->client_, self->inner_, self->up_);
            self->pump(self->inner_, self->client_, self->down_, true);
        });
    }

    /// Reads from `from` and writes what came to `to`, until either fails. civetweb's end of
    /// an answer (`to_client`) ends the TLS session properly: a client reads the close as the
    /// answer's end, not as a cut.
    template <class From, class To>
    void pump(From& from, To& to, std::array<char, 16384>& buffer, bool to_client = false) {
        from.async_read_some(asio::buffer(buffer),
                             [self = shared_from_this(), &from, &to, &buffer, to_client](
                                 boost::system::error_code ec, std::size_t n) {
                                 if (ec == asio::error::eof && to_client) return self->shut_down();
                                 if (ec) return self->close();
                                 asio::async_write(to, asio::buffer(buffer.data(), n),
                                                   [self, &from, &to, &buffer, to_client](
                                                       boost::system::error_code ec2, std::size_t) {
                                                       if (ec2) return self->close();
                                                       self->pump(from, to, buffer, to_client);
                                                   });
                             });
    }

    void shut_down() {
        client_.async_shutdown(
            [self = shared_from_this()](boost::system::error_code) { self->close(); });
    }

    void close() {
        boost::system::error_code ignored;
        timer_.cancel();
        client_.lowest_layer().close(ignored);
        inner_.close(ignored);
    }

    asio::ssl::stream<tcp::socket> client_;
    tcp::socket inner_;
    asio::steady_timer timer_;
    std::shared_ptr<int> count_;
    std::array<char, 16384> up_{};
    std::array<char, 16384> down_{};
};

/// `host:port` (an IPv6 host in brackets) as an endpoint to bind.
tcp::endpoint endpoint_of(asio::io_context& io, const std::string& listen) {
    const auto colon = listen.rfind(':');
    auto host = listen.substr(0, colon);
    if (host.size() >= 2 && host.front() == '[') host = host.substr(1, host.size() - 2);
    tcp::resolver resolver(io);
    return resolver.resolve(host, listen.substr(colon + 1)).begin()->endpoint();
}

}  // namespace

TlsFront::TlsFront(const std::string& listen, const std::string& cert, const std::string& key,
                   std::uint16_t inner_port)
    : tls_(asio::ssl::context::tls_server),
      acceptor_(io_),
      inner_(asio::ip::make_address("127.0.0.1"), inner_port),
      open_(std::make_shared<int>(0)) {
    // TLS 1.2 and 1.3 only: what every browser and Prometheus speak.
    tls_.set_options(asio::ssl::context::default_workarounds | asio::ssl::context::no_sslv2 |
                     asio::ssl::context::no_sslv3 | asio::ssl::context::no_tlsv1 |
                     asio::ssl::context::no_tlsv1_1);
    try {
        tls_.use_certificate_chain_file(cert);
    } catch (const boost::system::system_error& e) {
        throw std::runtime_error("cannot load the certificate " + cert + ": " + e.what());
    }
    try {
        tls_.use_private_key_file(key, asio::ssl::context::pem);
    } catch (const boost::system::system_error& e) {
        throw std::runtime_error("cannot load the key " + key + " for the certificate " + cert +
                                 ": " + e.what());
    }
    const auto at = endpoint_of(io_, listen);
    acceptor_.open(at.protocol());
    acceptor_.set_option(tcp::acceptor::reuse_address(true));
    acceptor_.bind(at);
    acceptor_.listen();
    port_ = acceptor_.local_endpoint().port();
    accept();
    thread_ = std::thread([this] { io_.run(); });
}

TlsFront::~TlsFront() {
    io_.stop();
    if (thread_.joinable()) thread_.join();
}

void TlsFront::accept() {
    acceptor_.async_accept([this](boost::system::error_code ec, tcp::socket socket) {
        if (ec) return;  // stopped
        if (open_.use_count() <= max_connections) {
            std::make_shared<Relay>(asio::ssl::stream<tcp::socket>(std::move(socket), tls_), open_)
                ->start(inner_);
        }
        accept();
    });
}

}  // namespace eip2mqtt::adapters::metrics::detail
