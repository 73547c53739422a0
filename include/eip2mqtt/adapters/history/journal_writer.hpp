#pragma once
/// Appends to the store-and-forward journal off the loop. An SQLite insert costs a few
/// microseconds: done on the loop for every datagram of an outage, it took more of the loop than
/// the journal may cost (docs/decisions/0002-journal-appends-off-the-loop.md). The loop hands over
/// each tick's entries at once; one worker thread appends and commits them, in order. The loop's
/// other uses of the journal (the replay's reads and deletions, figures) go through with(),
/// under the same lock, between two of the worker's batches.
///
/// Threading: append(), with(), flush() and the destructor from one thread (the loop); the
/// worker runs on its own.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/history/journal.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/throttled_log.hpp"

namespace eip2mqtt::adapters::history {

class JournalWriter {
public:
    /// `clock` (outliving it) times the worker's throttled failure log.
    explicit JournalWriter(std::unique_ptr<Journal> journal,
                           const core::Clock& clock = adapters::clock::system_clock());
    /// Appends and commits everything handed over, durably, then joins.
    ~JournalWriter();
    JournalWriter(const JournalWriter&) = delete;
    JournalWriter& operator=(const JournalWriter&) = delete;

    /// Hands `entries` over to be appended in order and committed (durably with `durable`),
    /// leaving `entries` empty (with the capacity of an earlier batch). Ids are given on append.
    void append(std::vector<JournalEntry>& entries, bool durable);

    /// Runs `f(journal)` now, on the caller's thread, while the worker waits.
    template <class F>
    auto with(F&& f) {
        std::lock_guard lock(journal_mutex_);
        return f(*journal_);
    }

    /// Blocks until everything handed over is appended and committed.
    void flush();
    /// True when everything handed over is appended and committed.
    bool idle() {
        std::lock_guard lock(queue_mutex_);
        return queued_.empty() && !busy_;
    }

    /// The id of the last entry written (0: none), without waiting for the worker.
    std::uint64_t last_id() const { return last_id_.load(std::memory_order_acquire); }

    /// Journal operations of the worker that failed (each logged at most once a minute).
    std::uint64_t failures() const { return failures_.load(std::memory_order_relaxed); }

private:
    void run();

    std::unique_ptr<Journal> journal_;
    std::mutex journal_mutex_;  ///< held by whoever uses journal_

    std::mutex queue_mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    std::vector<JournalEntry> queued_;  ///< handed over, not taken by the worker yet
    bool durable_ = false;
    bool busy_ = false;  ///< the worker holds a batch
    bool quit_ = false;
    std::atomic<std::uint64_t> failures_{0};
    std::atomic<std::uint64_t> last_id_{0};
    const core::Clock& clock_;
    core::ThrottledLog failure_log_;  ///< the worker's
    std::thread worker_;
};

}  // namespace eip2mqtt::adapters::history
