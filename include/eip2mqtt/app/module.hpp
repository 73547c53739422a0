#pragma once
/// One part of the running gateway with one life cycle: the composition root (Gateway) holds
/// its modules in dependency order, starts and ticks them in that order, stops them in reverse
/// and applies a reloaded configuration to each. A module that a configuration leaves out is
/// never made (its factory returns null), so nothing asks whether a feature is on.
///
/// Threading: every member is called on the loop.

#include <cstddef>
#include <optional>
#include <string_view>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/reload_slice.hpp"
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
    /// Whether it can take a reloaded configuration, already validated whole; false refuses
    /// the whole reload (logged by the module), before any module applied it. A module that
    /// said yes may already have taken it (a multicast group joined): only one refuses so far.
    virtual bool prepare(const core::config::Config& /*next*/) { return true; }
    /// The live settings of a reloaded configuration, which every module accepted.
    virtual void apply(const core::config::Config& /*next*/) {}
    /// After the reload's exchanges were applied: what it publishes again because of them.
    virtual void applied() {}
    /// What a reload left it to publish (retained topics cleared, new descriptions), made
    /// `units` at a time while its queue has room.
    virtual bool changes_pending() const { return false; }
    virtual void publish_changes(std::size_t /*units*/) {}
    /// The room in the publication queue a reload's slices wait on; nullopt: it has none.
    virtual std::optional<core::config::PublishQueueRoom> queue_room() const {
        return std::nullopt;
    }
    /// Its counters, for the metrics: borrowed until the next call (a module may keep a
    /// snapshot of figures it computes).
    virtual void add_metrics(MetricsSources& /*sources*/) {}

protected:
    Module() = default;
    Module(const Module&) = delete;
    Module& operator=(const Module&) = delete;
};

}  // namespace eip2mqtt::app
