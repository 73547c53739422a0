#pragma once
/// The rules of `mqtt` as a list of connections: each names itself (the name labels its
/// metrics and names its journal's file), once; the tags' layout is the first connection's, so
/// only it may set `topic_template`; `sparkplug.connection` names one of them.

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/diagnostic.hpp"

namespace eip2mqtt::core::config::detail {

/// Appends the problems of the connection list (nothing for a lone connection but an unknown
/// `sparkplug.connection`) to `out`.
void check_connection_list(const Config& config, Diagnostics& out);

}  // namespace eip2mqtt::core::config::detail
