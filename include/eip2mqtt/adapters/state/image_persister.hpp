#pragma once
/// Saves produced images off the loop (issue #6). ImageFile::save syncs the file to the disk,
/// which takes milliseconds: done on the loop, it would delay the datagrams of every other
/// exchange by as much. One worker thread saves instead, and each completion comes back to the
/// loop, where the write results waiting for it are published (docs/mqtt-api.md "Results": a
/// result only once the image is durably saved, or saying that it is not).
///
/// Each produced exchange attaches with the handler its completions go to, and saves under
/// the key it was given. Saves run in the order they were queued, one at a time.
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
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::adapters::state {

class ImagePersister {
public:
    using Key = std::uint64_t;
    /// The key of a save whose completion nobody hears (attach() never returns it).
    static constexpr Key unattended = 0;
    /// A finished save: nullopt when the image is on disk, else why not (ImageFile::save).
    using OnSaved = std::function<void(const std::optional<std::string>& error)>;

    /// Starts the worker. `store` must outlive this object.
    ImagePersister(const ImageStore& store, boost::asio::any_io_executor loop);
    /// Finishes every queued save (the last written values must reach the disk), then joins.
    /// Completions not delivered yet are dropped: call flush() first to publish them.
    ~ImagePersister();
    ImagePersister(const ImagePersister&) = delete;
    ImagePersister& operator=(const ImagePersister&) = delete;

    /// The file of `plan`'s image, read now (ImageStore::open): at an exchange's start.
    std::shared_ptr<ImageFile> open(const core::plan::ExchangePlan& plan) const {
        return store_.open(plan);
    }

    /// Registers the handler of one exchange's completions; returns the key it saves under.
    /// A handler must not detach itself.
    Key attach(OnSaved on_saved);
    /// Nothing more reaches the handler of `key`; its saves under way still reach the disk.
    void detach(Key key);

    /// Queues a save of `data` (copied) to `file` under `key`. `file` is kept alive by the job,
    /// so the exchange may be removed before its save is done.
    void save(Key key, std::shared_ptr<ImageFile> file, std::span<const std::byte> data);

    /// Blocks until every queued save is done, then delivers their completions at once, and
    /// again for the saves those handlers queued, until none is left (on stop, before the last
    /// publications are flushed; on reload, before images are handed over or read).
    void flush();

private:
    struct Saved {
        Key key;
        std::optional<std::string> error;
    };
    struct Job {
        Key key;
        std::shared_ptr<ImageFile> file;
        std::vector<std::byte> data;
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
