#pragma once
/// The eip2mqtt binary the tests run: the one this build made, or the one EIP2MQTT_TEST_BINARY
/// names. tools/test.sh runs the suites that only drive the binary (integration, conformance,
/// interop) once against the release binary and once, built by the release build, against the
/// sanitized binary, which spares the sanitizer build compiling those suites again.

#include <string>

namespace eip2mqtt::test {

/// The path of the binary under test.
const std::string& gateway_binary();

}  // namespace eip2mqtt::test
