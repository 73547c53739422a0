#pragma once
/// Paho C's in-memory trace, kept to errors unless the user asked for a trace.
///
/// Why: Debian's Paho C is built without HIGH_PERFORMANCE, so its trace level starts at
/// "minimum", and every Paho function's entry and exit, and every packet, writes an entry to
/// an in-memory ring under one process-wide mutex (with a time read and a formatted string):
/// Paho's three threads contend on it per publication. Nobody reads that ring unless
/// MQTT_C_CLIENT_TRACE names where to print it, so without it the level is raised to errors,
/// which skips the entries. Paho's heap tracking, the other cost of that build, has no switch.
///
/// Module-private (src/adapters/mqtt/detail).

namespace eip2mqtt::adapters::mqtt::detail {

/// Raises Paho C's trace level (process-wide) to errors, unless `requested_trace`, the value of
/// MQTT_C_CLIENT_TRACE, asks for a trace. Returns whether it did.
bool quiet_paho_trace(const char* requested_trace);

}  // namespace eip2mqtt::adapters::mqtt::detail
