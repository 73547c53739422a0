#pragma once
/// The Sender's sleeping and waking: its thread sleeps while nothing may go and is woken by
/// whoever makes room or work; stop() and wait_idle() sleep until a publication completes or
/// the thread goes idle. Names the protocol the condition variables and flags follow, so each
/// caller does one named step instead of pairing flags and notifications by hand.
///
/// Threading: every member but the notifications is called under the Sender's mutex (the
/// lock passed in); notify after unlocking. All inline: on the hot path each step costs what
/// the flag or the notification it wraps costs.
///
/// Module-private (src/adapters/mqtt/detail).

#include <chrono>
#include <condition_variable>
#include <mutex>

namespace eip2mqtt::adapters::mqtt::detail {

class SenderSignals {
public:
    using Lock = std::unique_lock<std::mutex>;

    // --- the sender's thread ---------------------------------------------------------------
    /// Goes idle (telling wait_idle()), sleeps until quit() or `ready()`, and wakes busy;
    /// returns false to quit.
    template <class Ready>
    bool sleep_until_ready(Lock& lock, Ready ready) {
        idle_ = true;
        if (idle_wanted_) completed_.notify_all();
        wake_.wait(lock, [&] { return quit_ || ready(); });
        idle_ = false;
        return !quit_;
    }
    /// Under the lock: whether the thread sleeps, so that new work must wake it.
    bool sleeping() const { return idle_; }
    /// Under the lock: the thread ends at its next wake-up.
    void quit() { quit_ = true; }
    bool quitting() const { return quit_; }

    // --- after unlocking -------------------------------------------------------------------
    /// Work or room for the thread.
    void wake_one() { wake_.notify_one(); }
    /// Sending resumes or stops, a hold ended, or quit().
    void wake_all() { wake_.notify_all(); }
    /// A pending publication finished, or the thread went idle.
    void completed() { completed_.notify_all(); }

    // --- the waiting threads (stop(), end_session()) ---------------------------------------
    /// Sleeps until `done()` or `deadline`.
    template <class Done>
    void wait_completed_until(Lock& lock, std::chrono::steady_clock::time_point deadline,
                              Done done) {
        completed_.wait_until(lock, deadline, done);
    }
    /// Sleeps until the thread is idle or quits.
    void wait_idle(Lock& lock) {
        idle_wanted_ = true;
        completed_.wait(lock, [this] { return idle_ || quit_; });
        idle_wanted_ = false;
    }

private:
    std::condition_variable wake_;       ///< work and room, or quit
    std::condition_variable completed_;  ///< a pending publication finished (for stop())
    bool idle_ = false;                  ///< the thread waits on wake_
    bool idle_wanted_ = false;           ///< wait_idle() waits on completed_ for idle_
    bool quit_ = false;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
