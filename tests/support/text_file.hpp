#pragma once
/// Whole text files, read and written by the test harness (brokers' configurations and logs).

#include <string>

namespace eip2mqtt::test {

/// The file's content; empty when it cannot be read (not there yet, say).
std::string read_text_file(const std::string& path);
/// Replaces the file's content with `content`.
void write_text_file(const std::string& path, const std::string& content);

}  // namespace eip2mqtt::test
