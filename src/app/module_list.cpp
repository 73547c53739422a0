#include "eip2mqtt/app/module_list.hpp"

namespace eip2mqtt::app {

ModuleList::ModuleList(std::vector<std::unique_ptr<Module>> modules) {
    for (auto& module : modules) {
        if (module) modules_.push_back(std::move(module));
    }
}

void ModuleList::start(core::MonoTime now) {
    std::size_t started = 0;
    try {
        for (; started < modules_.size(); ++started) modules_[started]->start(now);
    } catch (...) {
        // What started stops, in reverse, before the failure goes on up.
        while (started > 0) modules_[--started]->stop();
        throw;
    }
}

void ModuleList::tick(const TickTimes& times) {
    for (auto& module : modules_) module->tick(times);
}

void ModuleList::stop() {
    for (auto it = modules_.rbegin(); it != modules_.rend(); ++it) (*it)->stop();
}

bool ModuleList::prepare(const core::config::Config& next) {
    for (auto& module : modules_) {
        if (!module->prepare(next)) return false;
    }
    return true;
}

void ModuleList::apply(const core::config::Config& next) {
    for (auto& module : modules_) module->apply(next);
}

void ModuleList::applied() {
    for (auto& module : modules_) module->applied();
}

bool ModuleList::changes_pending() const {
    for (const auto& module : modules_) {
        if (module->changes_pending()) return true;
    }
    return false;
}

void ModuleList::publish_changes(std::size_t units) {
    for (auto& module : modules_) module->publish_changes(units);
}

std::optional<core::config::PublishQueueRoom> ModuleList::queue_room() const {
    for (const auto& module : modules_) {
        if (auto room = module->queue_room()) return room;
    }
    return std::nullopt;
}

void ModuleList::add_metrics(MetricsSources& sources) {
    for (auto& module : modules_) module->add_metrics(sources);
}

}  // namespace eip2mqtt::app
