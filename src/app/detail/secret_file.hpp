#pragma once
// Secrets the configuration names but never holds (the MQTT password, the status listener's):
// a systemd credential or a file, whose first line is the secret.

#include <string>
#include <string_view>

namespace eip2mqtt::app::detail {

/// Where systemd put the unit's credentials (LoadCredential=); empty outside such a unit.
std::string credentials_directory();

/// The first line of `path`; throws std::runtime_error("cannot read " + what) when it cannot.
std::string first_line(const std::string& path, const std::string& what);

/// The secret `file` names, given at the configuration's `key` (`mqtt.password_file`): the
/// systemd credential of that name when it has no slash and $CREDENTIALS_DIRECTORY is set, else
/// the file at that path (warned about when others may read it). Throws std::runtime_error
/// naming `key` when it cannot be read.
std::string read_secret_file(const std::string& file, std::string_view key);

}  // namespace eip2mqtt::app::detail
