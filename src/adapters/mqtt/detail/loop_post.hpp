#pragma once
/// Work handed to the loop by the client's parts from any thread (Paho's, the sender's). It runs
/// only while the client lives, and keeps the client alive while it runs: a Client destroyed
/// meanwhile leaves nothing behind that could touch it.
///
/// Module-private (src/adapters/mqtt/detail). bind() once, before any other thread posts;
/// post() and guarded() from any thread after that.

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/post.hpp>
#include <memory>
#include <utility>

namespace eip2mqtt::adapters::mqtt::detail {

class LoopPost {
public:
    explicit LoopPost(boost::asio::any_io_executor loop) : loop_(std::move(loop)) {}

    /// The object whose life bounds the work: the client's, right after it was made.
    void bind(std::weak_ptr<const void> owner) { owner_ = std::move(owner); }

    /// Runs `f()` on the loop, if the owner still lives then.
    template <class F>
    void post(F&& f) const {
        boost::asio::post(loop_, guarded(std::forward<F>(f)));
    }

    /// `f` wrapped to run only while the owner lives (a timer's completion handler).
    template <class F>
    auto guarded(F&& f) const {
        return [owner = owner_, f = std::forward<F>(f)](auto&&... args) mutable {
            if (auto alive = owner.lock()) {
                f(std::forward<decltype(args)>(args)...);
            }
        };
    }

    const boost::asio::any_io_executor& executor() const { return loop_; }

private:
    const boost::asio::any_io_executor loop_;
    std::weak_ptr<const void> owner_;
};

}  // namespace eip2mqtt::adapters::mqtt::detail
