#pragma once
/// Saves produced images off the loop (issue #6). ImageStore::save fsyncs the file and its
/// directory, which takes milliseconds on a disk: done on the loop, it would delay the
/// datagrams of every other exchange by as much. One worker thread saves instead, and each
/// completion comes back to the loop, where the write results waiting for it are published
/// (docs/mqtt-api.md "Results": a result only once the image is durably saved).
///
/// Each produced exchange attaches with the handler its completions go to, and saves under
/// the key it was given. Saves of one exchange run in order; a save queued while an older one
/// of the same exchange still waits replaces its data and adds its write ids (one fsync for
/// both).
///
/// Threading: every member on the loop only; handlers are called on the loop.

#include <boost/asio/any_io_executor.hpp>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <thread>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::adapters::state {

class ImagePersister {
public:
    using Key = std::uint64_t;
    /// A finished save: whether the file was written, and the ids given with the save (and
    /// with every save it absorbed), in order.
    using OnSaved = std::function<void(bool ok, const std::vector<std::uint64_t>& write_ids)>;

    /// Starts the worker. `store` must outlive this object.
    ImagePersister(const ImageStore& store, boost::asio::any_io_executor loop);
    /// Finishes every queued save (the last written values must reach the disk), then joins.
    /// Completions not delivered yet are dropped: call flush() first to publish them.
    ~ImagePersister();
    ImagePersister(const ImagePersister&) = delete;
    ImagePersister& operator=(const ImagePersister&) = delete;

    /// The image saved for `plan`, read now (ImageStore::load): at an exchange's start.
    std::optional<std::vector<std::byte>> load(const core::plan::ExchangePlan& plan) const {
        return store_.load(plan);
    }

    /// Registers the handler of one exchange's completions; returns the key it saves under.
    /// A handler must not detach itself.
    Key attach(OnSaved on_saved);
    /// Nothing more reaches the handler of `key`; its saves under way still reach the disk.
    void detach(Key key);

    /// Queues a save of `data` (copied) under `key`. `plan` is kept alive by the job, so the
    /// exchange may be removed before its save is done.
    void save(Key key, std::shared_ptr<const core::plan::ExchangePlan> plan,
              std::span<const std::byte> data, std::vector<std::uint64_t> write_ids);

    /// Blocks until every queued save is done, then delivers their completions at once (on
    /// stop, before the last publications are flushed; on reload, before images are read).
    void flush();

private:
    struct Saved {
        Key key;
        bool ok;
        std::vector<std::uint64_t> write_ids;
    };
    struct Job {
        Key key;
        std::shared_ptr<const core::plan::ExchangePlan> plan;
        std::vector<std::byte> data;
        std::vector<std::uint64_t> write_ids;
    };
    void run();
    void deliver();

    const ImageStore& store_;
    boost::asio::any_io_executor loop_;
    std::unordered_map<Key, OnSaved> handlers_;  ///< the loop's only
    Key next_key_ = 1;

    std::mutex mutex_;
    std::condition_variable work_;  ///< the worker waits for jobs
    std::condition_variable idle_;  ///< flush() waits for an empty queue and an idle worker
    std::deque<Job> queue_;         ///< guarded by mutex_
    std::vector<Saved> done_;       ///< guarded by mutex_
    bool busy_ = false;             ///< guarded by mutex_: the worker is saving
    bool delivery_posted_ = false;  ///< guarded by mutex_
    bool stopping_ = false;         ///< guarded by mutex_
    std::thread worker_;            ///< last: starts once everything above exists
};

}  // namespace eip2mqtt::adapters::state
