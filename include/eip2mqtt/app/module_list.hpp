#pragma once
/// The gateway's modules in dependency order, and each step of their life cycle over all of
/// them: started and ticked in order, stopped in reverse, a reload prepared by each before any
/// applies it, their counters gathered.
///
/// Threading: the loop only.

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "eip2mqtt/app/module.hpp"

namespace eip2mqtt::app {

class ModuleList {
public:
    ModuleList() = default;
    /// A null module is one the configuration leaves out (its factory returned null): dropped.
    explicit ModuleList(std::vector<std::unique_ptr<Module>> modules);

    /// Each in order. One that throws: those started before it stop, in reverse, and the
    /// exception goes on.
    void start(core::MonoTime now);
    void tick(const TickTimes& times);
    /// Each in reverse order.
    void stop();
    /// Whether every module takes `next`; asks each in order, up to the first that refuses.
    bool prepare(const core::config::Config& next);
    void apply(const core::config::Config& next);
    void applied();
    bool changes_pending() const;
    void publish_changes(std::size_t units);
    /// The first module's room that has a queue; nullopt when none has.
    std::optional<core::config::PublishQueueRoom> queue_room() const;
    void add_metrics(MetricsSources& sources);

    std::size_t size() const { return modules_.size(); }

private:
    std::vector<std::unique_ptr<Module>> modules_;
};

}  // namespace eip2mqtt::app
