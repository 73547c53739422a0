#pragma once
/// The parse of a reload, on a thread of its own: a SIGHUP's file is read and checked there, so
/// that the loop goes on receiving, producing and feeding /healthz while it parses (a file of
/// 100,000 inline tags takes seconds, one of 64 MiB tens of seconds). The loop is handed the
/// result and only applies it (reload::ReloadSequence, Gateway::apply).

#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::app {

/// A configuration file read and checked whole, with the plans of its exchanges (whose
/// configs it no longer holds: reload::take_plans).
struct ParsedConfig {
    core::config::Config config;
    std::vector<core::plan::ExchangePlan> plans;
};
using ParseResult = core::Result<ParsedConfig, core::config::Diagnostics>;

class ReloadWorker {
public:
    /// Reads and checks `path`, on the worker's thread. It may give up once `stop` is
    /// requested (the owner is stopping): what it returns then is dropped.
    using Parse = std::function<ParseResult(const std::string& path, std::stop_token stop)>;
    /// Hands a result to the owner, on the worker's thread (a post to the loop). Never called
    /// once stop() has returned.
    using Deliver = std::function<void(ParseResult)>;

    /// What request() did with a file.
    enum class Request {
        started,  ///< no parse was under way or waiting: this one starts now
        queued,   ///< a parse is under way: its result will be dropped, and this file parsed next
        merged,   ///< a parse was already waiting: this request is the same one
    };

    /// Starts the thread, idle until the first request.
    ReloadWorker(Parse parse, Deliver deliver);
    /// stop().
    ~ReloadWorker();
    ReloadWorker(const ReloadWorker&) = delete;
    ReloadWorker& operator=(const ReloadWorker&) = delete;

    /// From the owner's thread: parse `path`. Requests made while a parse runs are coalesced:
    /// once it ends, its result is dropped (the file was signalled again after it was read)
    /// and the file of the last request is parsed; one result is delivered for them all.
    Request request(std::string path);

    /// From the owner's thread: runs `job` on the worker's thread, before the next parse (once
    /// the parse under way, if any, ends). For the work that would stop the loop after a
    /// reload: malloc_trim, which walks every arena for tens of milliseconds. A job not begun
    /// when stop() is called is dropped.
    void post(std::function<void()> job);

    /// Asks a parse under way to give up, and waits for the thread to end; nothing is delivered
    /// after. Requests made after it are never parsed.
    void stop();

private:
    void run(std::stop_token stop);

    Parse parse_;
    Deliver deliver_;
    std::mutex mutex_;
    std::condition_variable_any wake_;
    std::optional<std::string> waiting_;       ///< guarded by mutex_: the next file to parse
    std::vector<std::function<void()>> jobs_;  ///< guarded by mutex_: post()ed, not yet run
    bool parsing_ = false;                     ///< guarded by mutex_
    std::jthread thread_;                      ///< last: starts once the rest is built
};

}  // namespace eip2mqtt::app
