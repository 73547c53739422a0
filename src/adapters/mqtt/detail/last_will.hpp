#pragma once
/// The last will made for the current connection (ClientOptions::will), kept until a clean
/// stop() or end_session() says it, or an attempt that never connected forgets it.
///
/// Threading: set() on the loop; take() and forget() on the loop or the stopping thread (the
/// loop may no longer run): one short lock.
///
/// Module-private (src/adapters/mqtt/detail).

#include <mutex>
#include <optional>
#include <utility>

#include "eip2mqtt/adapters/mqtt/message.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class LastWill {
public:
    /// The will of the connection being made.
    void set(Message will) {
        std::lock_guard lock(mutex_);
        will_ = std::move(will);
    }
    /// The will, to be said now; none when there is none or it was taken.
    std::optional<Message> take() {
        std::lock_guard lock(mutex_);
        return std::exchange(will_, std::nullopt);
    }
    /// The attempt it was made for never connected: never to be said.
    void forget() {
        std::lock_guard lock(mutex_);
        will_.reset();
    }

private:
    std::mutex mutex_;
    std::optional<Message> will_;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
