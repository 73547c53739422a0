#pragma once
/// Test PKI made at test time with the openssl command line: a CA, a server certificate for
/// 127.0.0.1 and localhost, a client certificate, and a second CA with a server certificate of
/// its own (the same names, an issuer the gateway does not trust). EC P-256 keys: fast to make.

#include <string>

namespace eip2mqtt::test {

struct TlsCerts {
    /// Generates every file into `dir` (which must exist); throws with openssl's output if a
    /// command fails.
    explicit TlsCerts(const std::string& dir);

    std::string ca_cert;      ///< the trusted CA
    std::string server_cert;  ///< signed by ca_cert; SAN IP:127.0.0.1, DNS:localhost
    std::string server_key;
    std::string client_cert;  ///< signed by ca_cert; CN eip2mqtt-client, clientAuth
    std::string client_key;
    std::string other_ca_cert;      ///< a CA nobody trusts
    std::string other_server_cert;  ///< signed by other_ca_cert; same names as server_cert
    std::string other_server_key;
};

}  // namespace eip2mqtt::test
