#include "tests/support/tls_certs.hpp"

#include <fstream>
#include <stdexcept>
#include <vector>

#include "tests/support/child_process.hpp"

namespace eip2mqtt::test {
namespace {

constexpr const char* kOpenssl = "/usr/bin/openssl";
constexpr auto kCommandTimeout = std::chrono::seconds(30);

void openssl(std::vector<std::string> args) {
    args.insert(args.begin(), kOpenssl);
    std::string line;
    for (const auto& a : args) line += a + " ";
    const auto result = run_command(std::move(args), kCommandTimeout);
    if (result.status != 0) {
        throw std::runtime_error("TlsCerts: `" + line + "` failed (" +
                                 std::to_string(result.status) + "):\n" + result.output);
    }
}

void make_ca(const std::string& dir, const std::string& name, const std::string& cn) {
    openssl({"req", "-x509", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
             "-keyout", dir + "/" + name + ".key", "-out", dir + "/" + name + ".crt", "-days", "2",
             "-subj", "/CN=" + cn, "-addext", "basicConstraints=critical,CA:TRUE", "-addext",
             "keyUsage=critical,keyCertSign,cRLSign"});
}

/// A key and a certificate `name`.{key,crt} signed by the CA `ca`, with the extensions of
/// `extensions` (openssl extfile syntax).
void make_leaf(const std::string& dir, const std::string& ca, const std::string& name,
               const std::string& cn, const std::string& extensions) {
    const std::string base = dir + "/" + name;
    std::ofstream(base + ".ext") << extensions;
    openssl({"req", "-new", "-newkey", "ec", "-pkeyopt", "ec_paramgen_curve:prime256v1", "-nodes",
             "-keyout", base + ".key", "-out", base + ".csr", "-subj", "/CN=" + cn});
    openssl({"x509", "-req", "-in", base + ".csr", "-CA", dir + "/" + ca + ".crt", "-CAkey",
             dir + "/" + ca + ".key", "-CAcreateserial", "-out", base + ".crt", "-days", "2",
             "-extfile", base + ".ext"});
}

constexpr const char* kServerExtensions =
    "basicConstraints=CA:FALSE\n"
    "keyUsage=critical,digitalSignature\n"
    "extendedKeyUsage=serverAuth\n"
    "subjectAltName=IP:127.0.0.1,DNS:localhost\n";
constexpr const char* kClientExtensions =
    "basicConstraints=CA:FALSE\n"
    "keyUsage=critical,digitalSignature\n"
    "extendedKeyUsage=clientAuth\n";

}  // namespace

TlsCerts::TlsCerts(const std::string& dir) {
    make_ca(dir, "ca", "eip2mqtt test CA");
    make_leaf(dir, "ca", "server", "localhost", kServerExtensions);
    make_leaf(dir, "ca", "client", "eip2mqtt-client", kClientExtensions);
    make_ca(dir, "other-ca", "eip2mqtt untrusted CA");
    make_leaf(dir, "other-ca", "other-server", "localhost", kServerExtensions);

    ca_cert = dir + "/ca.crt";
    server_cert = dir + "/server.crt";
    server_key = dir + "/server.key";
    client_cert = dir + "/client.crt";
    client_key = dir + "/client.key";
    other_ca_cert = dir + "/other-ca.crt";
    other_server_cert = dir + "/other-server.crt";
    other_server_key = dir + "/other-server.key";
}

}  // namespace eip2mqtt::test
