#pragma once
// A fake Module (app/module.hpp) that writes what it is asked, in order, to a journal shared by
// several: the life cycle of a list of modules can then be read as one sequence.

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <initializer_list>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/module.hpp"

namespace eip2mqtt::test {

using namespace std::chrono_literals;
using app::MetricsSources;
using app::TickTimes;

/// What the modules were asked, in order, from the loop's thread and the test's.
class ModuleJournal {
public:
    void add(std::string event) {
        {
            std::lock_guard lock(mutex_);
            events_.push_back(std::move(event));
        }
        changed_.notify_all();
    }
    /// True once `event` was added, within 30 s.
    bool wait_for(const std::string& event) {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(lock, 30s, [&] {
            return std::find(events_.begin(), events_.end(), event) != events_.end();
        });
    }
    /// The events that start with one of `prefixes`, in order.
    std::vector<std::string> only(std::initializer_list<std::string_view> prefixes) {
        std::lock_guard lock(mutex_);
        std::vector<std::string> out;
        for (const auto& event : events_) {
            for (auto prefix : prefixes) {
                if (event.starts_with(prefix)) out.push_back(event);
            }
        }
        return out;
    }

private:
    std::mutex mutex_;
    std::condition_variable changed_;
    std::vector<std::string> events_;
};

struct FakeBehaviour {
    bool fail_start = false;
    bool refuse = false;
};

class FakeModule final : public app::Module {
public:
    FakeModule(std::string name, ModuleJournal& journal, FakeBehaviour behaviour = {})
        : name_(std::move(name)), journal_(journal), behaviour_(behaviour) {}

    void start(core::MonoTime) override {
        if (behaviour_.fail_start) throw std::runtime_error(name_ + " cannot start");
        journal_.add("start " + name_);
    }
    void tick(const TickTimes&) override {
        if (ticks_ < 2) journal_.add("tick " + name_ + " " + std::to_string(++ticks_));
    }
    void stop() override { journal_.add("stop " + name_); }
    bool prepare(const core::config::Config& next) override {
        journal_.add("prepare " + name_ + " " + next.gateway.log_level);
        return !behaviour_.refuse;
    }
    void apply(const core::config::Config& next) override {
        journal_.add("apply " + name_ + " " + next.gateway.log_level);
    }
    void applied() override { journal_.add("applied " + name_); }
    void add_metrics(MetricsSources& sources) override { sources.commands = &commands_; }

    core::command::CommandCounters commands_;

private:
    std::string name_;
    ModuleJournal& journal_;
    FakeBehaviour behaviour_;
    int ticks_ = 0;
};

}  // namespace eip2mqtt::test
