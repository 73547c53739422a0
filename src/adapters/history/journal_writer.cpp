#include "eip2mqtt/adapters/history/journal_writer.hpp"

#include <pthread.h>
#include <spdlog/spdlog.h>

#include <chrono>

namespace eip2mqtt::adapters::history {

JournalWriter::JournalWriter(std::unique_ptr<Journal> journal, const core::Clock& clock)
    : journal_(std::move(journal)),
      last_id_(journal_->last_id()),
      clock_(clock),
      worker_([this] { run(); }) {}

JournalWriter::~JournalWriter() {
    {
        std::lock_guard lock(queue_mutex_);
        quit_ = true;
        durable_ = true;  // the last batch reaches the disk
    }
    wake_.notify_one();
    worker_.join();
}

void JournalWriter::append(std::vector<JournalEntry>& entries, bool durable) {
    {
        std::lock_guard lock(queue_mutex_);
        durable_ = durable_ || durable;
        if (queued_.empty()) {
            queued_.swap(entries);  // the usual case: the worker took the last batch already
        } else {
            for (auto& entry : entries) queued_.push_back(std::move(entry));
        }
    }
    entries.clear();
    wake_.notify_one();
}

void JournalWriter::flush() {
    std::unique_lock lock(queue_mutex_);
    done_.wait(lock, [this] { return queued_.empty() && !busy_ && !durable_; });
}

void JournalWriter::run() {
    // Named for `top -H` and profiles (at most 15 characters).
    ::pthread_setname_np(::pthread_self(), "journal");
    std::vector<JournalEntry> batch;
    std::unique_lock lock(queue_mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return quit_ || !queued_.empty() || durable_; });
        const bool quit = quit_;
        const bool durable = durable_;
        batch.swap(queued_);
        durable_ = false;
        busy_ = true;
        lock.unlock();
        try {
            std::lock_guard journal(journal_mutex_);
            journal_->write(batch, durable);
            last_id_.store(journal_->last_id(), std::memory_order_release);
        } catch (const std::exception& error) {
            failures_.fetch_add(1, std::memory_order_relaxed);
            if (const auto count = failure_log_.record(clock_.monotonic())) {
                spdlog::error(
                    "store and forward: the journal failed: {} ({} since the last report); live "
                    "data goes on",
                    error.what(), count);
            }
        }
        lock.lock();
        batch.clear();
        busy_ = false;
        done_.notify_all();
        if (quit && queued_.empty()) return;
    }
}

}  // namespace eip2mqtt::adapters::history
