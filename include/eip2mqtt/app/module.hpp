#pragma once
/// One part of the running gateway with one life cycle: the composition root (Gateway) holds
/// its modules in dependency order, starts and ticks them in that order, stops them in reverse
/// and applies a reloaded configuration to each. A module that a configuration leaves out is
/// never made (its factory returns null), so nothing asks whether a feature is on.
///
/// Threading: every member is called on the loop.

#include <string_view>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app {

struct MetricsSources;

/// The times of one tick of the loop (every 10 ms).
struct TickTimes {
    core::MonoTime now;
    core::WallTime wall;
    /// Once a second: what is counted in whole seconds is scanned on this tick.
    bool refresh_scan = false;
};

class Module {
public:
    virtual ~Module() = default;

    /// Its sockets open and its handlers set, once the loop is about to run.
    virtual void start(core::MonoTime /*now*/) {}
    virtual void tick(const TickTimes& /*times*/) {}
    /// Its sockets closed, before the modules it depends on stop.
    virtual void stop() {}
    /// The live settings of a reloaded configuration, already validated whole.
    virtual void apply(const core::config::Config& /*next*/) {}
    /// Its counters, for the metrics (borrowed for one call).
    virtual void add_metrics(MetricsSources& /*sources*/) const {}

protected:
    Module() = default;
    Module(const Module&) = delete;
    Module& operator=(const Module&) = delete;
};

}  // namespace eip2mqtt::app
