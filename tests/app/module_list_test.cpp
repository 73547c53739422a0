// The modules' life cycle over the list: in order, stop in reverse, a failing start unwinds,
// a reload prepared by each up to the first refusal, and the first queue's room.

#include "eip2mqtt/app/module_list.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/support/fakes/fake_module.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using test::FakeBehaviour;
using test::FakeModule;
using test::ModuleJournal;

ModuleList three(ModuleJournal& journal, FakeBehaviour b = {}) {
    std::vector<std::unique_ptr<Module>> modules;
    modules.push_back(std::make_unique<FakeModule>("A", journal));
    modules.push_back(std::make_unique<FakeModule>("B", journal, b));
    modules.push_back(std::make_unique<FakeModule>("C", journal));
    return ModuleList(std::move(modules));
}

TEST(ModuleList, StartsAndTicksInOrderAndStopsInReverse) {
    ModuleJournal journal;
    auto list = three(journal);
    list.start(core::MonoTime{});
    list.tick({});
    list.stop();
    EXPECT_EQ(journal.only({"start", "tick", "stop"}),
              (std::vector<std::string>{"start A", "start B", "start C", "tick A 1", "tick B 1",
                                        "tick C 1", "stop C", "stop B", "stop A"}));
}

TEST(ModuleList, AFailingStartStopsOnlyWhatStartedBeforeItInReverse) {
    ModuleJournal journal;
    auto list = three(journal, {.fail_start = true});
    EXPECT_THROW(list.start(core::MonoTime{}), std::runtime_error);
    EXPECT_EQ(journal.only({"start", "stop"}), (std::vector<std::string>{"start A", "stop A"}));
}

TEST(ModuleList, APreparationStopsAtTheFirstRefusal) {
    ModuleJournal journal;
    auto list = three(journal, {.refuse = true});
    core::config::Config next;
    next.gateway.log_level = "debug";
    EXPECT_FALSE(list.prepare(next));
    EXPECT_EQ(journal.only({"prepare"}),
              (std::vector<std::string>{"prepare A debug", "prepare B debug"}));
}

TEST(ModuleList, AModuleLeftOutIsDropped) {
    ModuleJournal journal;
    std::vector<std::unique_ptr<Module>> modules;
    modules.push_back(std::make_unique<FakeModule>("A", journal));
    modules.push_back(nullptr);
    ModuleList list(std::move(modules));
    EXPECT_EQ(list.size(), 1u);
    list.start(core::MonoTime{});
    list.stop();
    EXPECT_EQ(journal.only({"start", "stop"}), (std::vector<std::string>{"start A", "stop A"}));
}

TEST(ModuleList, ModulesWithoutAQueueHaveNoRoomAndNoChanges) {
    ModuleJournal journal;
    auto list = three(journal);
    EXPECT_FALSE(list.queue_room().has_value());
    EXPECT_FALSE(list.changes_pending());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
