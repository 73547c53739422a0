#include "eip2mqtt/app/reload/reload_worker.hpp"

#include <utility>

namespace eip2mqtt::app {

ReloadWorker::ReloadWorker(Parse parse, Deliver deliver)
    : parse_(std::move(parse)),
      deliver_(std::move(deliver)),
      thread_([this](std::stop_token stop) { run(std::move(stop)); }) {}

ReloadWorker::~ReloadWorker() { stop(); }

ReloadWorker::Request ReloadWorker::request(std::string path) {
    Request outcome = Request::started;
    {
        std::lock_guard lock(mutex_);
        if (waiting_) {
            outcome = Request::merged;
        } else if (parsing_) {
            outcome = Request::queued;
        }
        waiting_ = std::move(path);
    }
    wake_.notify_one();
    return outcome;
}

void ReloadWorker::post(std::function<void()> job) {
    {
        std::lock_guard lock(mutex_);
        jobs_.push_back(std::move(job));
    }
    wake_.notify_one();
}

void ReloadWorker::stop() {
    thread_.request_stop();  // wakes the wait below, and a parse that polls its token
    if (thread_.joinable()) thread_.join();
}

void ReloadWorker::run(std::stop_token stop) {
    for (;;) {
        std::string path;
        std::vector<std::function<void()>> jobs;
        {
            std::unique_lock lock(mutex_);
            const auto ready = [this] { return waiting_.has_value() || !jobs_.empty(); };
            if (!wake_.wait(lock, stop, ready)) return;
            jobs.swap(jobs_);
        }
        for (auto& job : jobs) job();
        {
            std::lock_guard lock(mutex_);
            if (stop.stop_requested()) return;
            if (!waiting_) continue;
            path = std::move(*waiting_);
            waiting_.reset();
            parsing_ = true;
        }
        auto result = parse_(path, stop);
        {
            std::lock_guard lock(mutex_);
            parsing_ = false;
            if (stop.stop_requested()) return;
            // Signalled again while it parsed: the file changed after it was read, so this
            // result is stale; the newest file is parsed at once, and only its result applied.
            if (waiting_) continue;
        }
        deliver_(std::move(result));
    }
}

}  // namespace eip2mqtt::app
