#include "eip2mqtt/app/reload/reload_worker.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// A parse that records the files it is asked for and, while `held`, waits to be released (or
/// stopped); and a delivery that records the files of the results it is handed.
class Recorder {
public:
    ReloadWorker::Parse parse() {
        return [this](const std::string& path, std::stop_token stop) -> ParseResult {
            std::unique_lock lock(mutex_);
            parsed_.push_back(path);
            changed_.notify_all();
            changed_.wait(lock, stop, [this] { return !held_; });
            if (stop.stop_requested()) ++given_up_;
            ParsedConfig config;
            config.config.file = path;
            return config;
        };
    }
    ReloadWorker::Deliver deliver() {
        return [this](ParseResult result) {
            std::lock_guard lock(mutex_);
            delivered_.push_back(result->config.file);
            changed_.notify_all();
        };
    }
    void release() {
        std::lock_guard lock(mutex_);
        held_ = false;
        changed_.notify_all();
    }
    /// Waits (bounded) until `parses` parses began and `deliveries` results were delivered.
    bool wait(std::size_t parses, std::size_t deliveries) {
        std::unique_lock lock(mutex_);
        return changed_.wait_for(
            lock, 10s, [&] { return parsed_.size() >= parses && delivered_.size() >= deliveries; });
    }
    std::vector<std::string> parsed() {
        std::lock_guard lock(mutex_);
        return parsed_;
    }
    std::vector<std::string> delivered() {
        std::lock_guard lock(mutex_);
        return delivered_;
    }
    int given_up() {
        std::lock_guard lock(mutex_);
        return given_up_;
    }

private:
    std::mutex mutex_;
    std::condition_variable_any changed_;
    bool held_ = true;
    int given_up_ = 0;
    std::vector<std::string> parsed_;
    std::vector<std::string> delivered_;
};

TEST(ReloadWorker, ParsesOnItsOwnThreadAndDeliversTheResult) {
    Recorder recorder;
    const auto caller = std::this_thread::get_id();
    std::thread::id parsed_on;
    ReloadWorker worker(
        [&, parse = recorder.parse()](const std::string& path, std::stop_token stop) {
            parsed_on = std::this_thread::get_id();
            return parse(path, stop);
        },
        recorder.deliver());
    recorder.release();
    EXPECT_EQ(worker.request("a.yaml"), ReloadWorker::Request::started);
    ASSERT_TRUE(recorder.wait(1, 1));
    EXPECT_NE(parsed_on, caller);
    EXPECT_EQ(recorder.delivered(), std::vector<std::string>{"a.yaml"});
    // Idle again: the next request starts a parse of its own.
    EXPECT_EQ(worker.request("b.yaml"), ReloadWorker::Request::started);
    ASSERT_TRUE(recorder.wait(2, 2));
    EXPECT_EQ(recorder.delivered(), (std::vector<std::string>{"a.yaml", "b.yaml"}));
}

TEST(ReloadWorker, RequestsDuringAParseAreCoalescedIntoOneParseOfTheLastFile) {
    Recorder recorder;
    ReloadWorker worker(recorder.parse(), recorder.deliver());
    EXPECT_EQ(worker.request("first.yaml"), ReloadWorker::Request::started);
    ASSERT_TRUE(recorder.wait(1, 0));  // the first parse is under way, held
    EXPECT_EQ(worker.request("second.yaml"), ReloadWorker::Request::queued);
    EXPECT_EQ(worker.request("third.yaml"), ReloadWorker::Request::merged);
    recorder.release();
    ASSERT_TRUE(recorder.wait(2, 1));
    // The first result is stale (signalled again after it was read): dropped; the last file is
    // parsed once, and its result is the one delivered.
    worker.stop();
    EXPECT_EQ(recorder.parsed(), (std::vector<std::string>{"first.yaml", "third.yaml"}));
    EXPECT_EQ(recorder.delivered(), std::vector<std::string>{"third.yaml"});
}

TEST(ReloadWorker, StopGivesUpAParseUnderWayAndDeliversNothing) {
    Recorder recorder;  // held: the parse waits until it is stopped
    ReloadWorker worker(recorder.parse(), recorder.deliver());
    worker.request("large.yaml");
    ASSERT_TRUE(recorder.wait(1, 0));
    worker.request("newer.yaml");
    worker.stop();  // returns: the parse saw its stop token
    EXPECT_EQ(recorder.given_up(), 1);
    EXPECT_EQ(recorder.parsed(), std::vector<std::string>{"large.yaml"});
    EXPECT_TRUE(recorder.delivered().empty());
}

TEST(ReloadWorker, APostedJobRunsOnItsThreadAndParsesGoOnAfterIt) {
    Recorder recorder;
    recorder.release();
    ReloadWorker worker(recorder.parse(), recorder.deliver());
    const auto caller = std::this_thread::get_id();
    std::mutex mutex;
    std::condition_variable ran;
    std::vector<std::string> order;
    std::thread::id job_on;
    worker.post([&] {
        std::lock_guard lock(mutex);
        job_on = std::this_thread::get_id();
        order.push_back("job");
        ran.notify_all();
    });
    {
        std::unique_lock lock(mutex);
        ASSERT_TRUE(ran.wait_for(lock, 10s, [&] { return !order.empty(); }));
    }
    EXPECT_NE(job_on, caller);
    // The worker goes on parsing after it.
    EXPECT_EQ(worker.request("a.yaml"), ReloadWorker::Request::started);
    ASSERT_TRUE(recorder.wait(1, 1));
    EXPECT_EQ(recorder.delivered(), std::vector<std::string>{"a.yaml"});
}

TEST(ReloadWorker, DestroyingAnIdleWorkerEndsItsThread) {
    Recorder recorder;
    { ReloadWorker worker(recorder.parse(), recorder.deliver()); }
    EXPECT_TRUE(recorder.parsed().empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
