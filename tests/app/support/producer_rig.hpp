#pragma once
// What an ExchangeProducer needs around it in a unit test: a state directory of the test's own
// (removed at the end), an image store and persister on it, a UDP sender on loopback and a
// scheduler, all on one io_context the test runs when it wants. make() builds a producer on them.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <filesystem>
#include <memory>
#include <string>
#include <system_error>

#include "eip2mqtt/adapters/state/image_persister.hpp"
#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/adapters/udp/sender.hpp"
#include "eip2mqtt/app/exchanges/exchange_producer.hpp"
#include "eip2mqtt/app/exchanges/producer_scheduler.hpp"

namespace eip2mqtt::test {

class ProducerRig {
public:
    /// The directory is named after `prefix`, the running test and the process.
    explicit ProducerRig(const std::string& prefix)
        : dir_(std::filesystem::temp_directory_path() /
               (prefix + "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name() +
                "_" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
        store_ = std::make_unique<adapters::state::ImageStore>(dir_.string());
        adapters::udp::SenderOptions sender_options;
        sender_options.bind = "127.0.0.1";
        sender_ = std::make_unique<adapters::udp::Sender>(loop_.get_executor(), sender_options);
        scheduler_ = std::make_unique<app::ProducerScheduler>(loop_.get_executor(), *sender_);
        persister_ =
            std::make_unique<adapters::state::ImagePersister>(*store_, loop_.get_executor());
    }
    /// Producers made here must be gone first (they hold the scheduler and the persister).
    ~ProducerRig() {
        persister_.reset();
        scheduler_.reset();
        std::error_code ignored;
        std::filesystem::remove_all(dir_, ignored);
    }
    ProducerRig(const ProducerRig&) = delete;
    ProducerRig& operator=(const ProducerRig&) = delete;

    /// A producer of `plan` to 127.0.0.1:9, its image restored (or initial) and saved.
    std::unique_ptr<app::ExchangeProducer> make(core::plan::ExchangePlan plan,
                                                app::Northbound& northbound) {
        auto producer = std::make_unique<app::ExchangeProducer>(
            std::move(plan), adapters::udp::Endpoint{0x7F000001, 9}, *scheduler_, *persister_,
            northbound, totals_);
        persister_->flush();
        return producer;
    }

    boost::asio::io_context& loop() { return loop_; }
    adapters::state::ImageStore& store() { return *store_; }
    adapters::state::ImagePersister& persister() { return *persister_; }
    app::ImageSaveTotals& totals() { return totals_; }

private:
    std::filesystem::path dir_;
    boost::asio::io_context loop_;
    std::unique_ptr<adapters::state::ImageStore> store_;
    std::unique_ptr<adapters::udp::Sender> sender_;
    std::unique_ptr<app::ProducerScheduler> scheduler_;
    std::unique_ptr<adapters::state::ImagePersister> persister_;
    app::ImageSaveTotals totals_;
};

}  // namespace eip2mqtt::test
