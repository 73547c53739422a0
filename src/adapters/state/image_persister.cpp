#include "eip2mqtt/adapters/state/image_persister.hpp"

#include <boost/asio/post.hpp>
#include <utility>

namespace eip2mqtt::adapters::state {

ImagePersister::ImagePersister(const ImageStore& store, boost::asio::any_io_executor loop)
    : store_(store), loop_(std::move(loop)), worker_([this] { run(); }) {}

ImagePersister::~ImagePersister() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    work_.notify_one();
    worker_.join();
}

ImagePersister::Key ImagePersister::attach(OnSaved on_saved) {
    const auto key = next_key_++;
    handlers_.emplace(key, std::move(on_saved));
    return key;
}

void ImagePersister::detach(Key key) { handlers_.erase(key); }

void ImagePersister::save(Key key, std::shared_ptr<ImageFile> file,
                          std::span<const std::byte> data) {
    {
        std::lock_guard lock(mutex_);
        queue_.push_back({key, std::move(file), {data.begin(), data.end()}});
    }
    work_.notify_one();
}

void ImagePersister::flush() {
    // A completion may queue the save it held back (one under way per exchange): until a
    // delivery queues nothing more. Each round runs no longer than its saves.
    for (;;) {
        {
            std::unique_lock lock(mutex_);
            idle_.wait(lock, [this] { return queue_.empty() && !busy_; });
            if (done_.empty()) return;
        }
        deliver();
    }
}

void ImagePersister::run() {
    std::unique_lock lock(mutex_);
    for (;;) {
        work_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;  // stopping, and every save is done
        Job job = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        lock.unlock();
        auto error = job.file->save(job.data);
        job.file.reset();  // closed here, off the loop, when it was the last reference
        lock.lock();
        busy_ = false;
        done_.push_back({job.key, std::move(error)});
        if (!delivery_posted_ && !stopping_) {
            // One delivery handler for however many completions pile up before it runs.
            delivery_posted_ = true;
            boost::asio::post(loop_, [this] { deliver(); });
        }
        if (queue_.empty()) idle_.notify_all();
    }
}

void ImagePersister::deliver() {
    std::vector<Saved> done;
    {
        std::lock_guard lock(mutex_);
        done.swap(done_);
        delivery_posted_ = false;
    }
    for (const auto& saved : done) {
        const auto it = handlers_.find(saved.key);
        if (it != handlers_.end()) it->second(saved.error);
    }
}

}  // namespace eip2mqtt::adapters::state
