#pragma once
/// The course of a reload, SIGHUP to READY (docs/operations.md, Reload): the file is handed to
/// the ReloadWorker, which reads and checks it off the loop (a SIGHUP while it parses has it
/// parsed again once that parse ends); its result is applied on the loop by the target, whole
/// or not at all; what the change publishes follows in slices (core::config::slice_units), the
/// loop receiving and producing between two, and waits a tick while the publish queue is half
/// full; a result that arrives meanwhile waits for the end. Then the parse's heap is given
/// back, the outcome logged and READY said once no other reload is under way.
///
/// Threading: the loop, but for the parse (on the worker's thread).

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "eip2mqtt/app/reload/reload_worker.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/config/reload_slice.hpp"

namespace eip2mqtt::app::reload {

/// What a reload changes: the gateway.
class ReloadTarget {
public:
    /// The configuration file a SIGHUP reads again.
    virtual const std::string& file() const = 0;
    /// A reload starts (systemd's RELOADING).
    virtual void reloading() = 0;
    /// Applies a parse's result whole or refuses it (logged); appends the lines that log what
    /// was applied, once the reload is done, to `outcome`. True when the exchanges were
    /// replaced (their old heap is then given back).
    virtual bool apply(ParseResult parsed, std::vector<std::string>& outcome) = 0;
    /// Whether the change has publications left, and one slice of at most `units` of them.
    virtual bool changes_pending() const = 0;
    virtual void publish_changes(std::size_t units) = 0;
    /// How full the publish queue is, to size the next slice.
    virtual core::config::PublishQueueRoom queue_room() const = 0;
    /// No reload is under way any more (systemd's READY).
    virtual void ready() = 0;
    /// The gateway is stopping: a reload under way goes no further.
    virtual bool stopping() const = 0;

protected:
    ~ReloadTarget() = default;
};

class ReloadSequence {
public:
    /// `loop` runs the target; the target and `clock` outlive the sequence. `parse_file` reads
    /// and checks a file on the worker's thread.
    ReloadSequence(boost::asio::any_io_executor loop, ReloadTarget& target,
                   const core::Clock& clock, ReloadWorker::Parse parse_file = parse);

    /// SIGHUP.
    void request();
    /// A parse under way is given up; nothing is applied after.
    void stop() { worker_.stop(); }

    /// ReloadWorker::Parse: the file loaded, its plans made (take_plans).
    static ParseResult parse(const std::string& path, std::stop_token stop);

private:
    struct Parsed {
        ParseResult result;
        std::chrono::steady_clock::duration parse_took;
    };
    /// The reload being applied, from its result on the loop to finish().
    struct Applying {
        core::MonoTime from;
        std::chrono::steady_clock::duration parse_took;
        std::vector<std::string> outcome;
        bool applied = false;
        int slices = 0;
        std::chrono::steady_clock::duration longest_slice{};
    };

    void on_parsed(ParseResult parsed);
    void begin(Parsed parsed);
    void next_slice();
    void finish();

    boost::asio::any_io_executor loop_;
    ReloadTarget& target_;
    const core::Clock& clock_;
    /// Results the loop still waits for (or has, waiting in parsed_).
    int pending_ = 0;
    core::MonoTime requested_at_;
    std::optional<Applying> applying_;
    std::deque<Parsed> parsed_;        ///< arrived while applying_ was under way
    boost::asio::steady_timer timer_;  ///< waits for the publish queue to drain
    /// Last: its thread is stopped and joined first, before anything its results reach.
    ReloadWorker worker_;
};

/// The plans of `config`'s exchanges, for Exchanges::apply. The exchange configs (every tag
/// again, with the marks of its keys) served validation only: they are released here.
std::vector<core::plan::ExchangePlan> take_plans(core::config::Config& config);

}  // namespace eip2mqtt::app::reload
