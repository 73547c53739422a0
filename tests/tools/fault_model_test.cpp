#include "tools/fault_injector/fault_model.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace eip2mqtt::fault_injector {
namespace {

// A 32-byte header (rid = i) + 8 data bytes, distinguishable by index.
std::vector<std::byte> datagram(std::uint16_t i) {
    std::vector<std::byte> d(40, std::byte{0});
    d[0] = std::byte{0x0D};
    d[1] = std::byte{0x01};
    d[2] = static_cast<std::byte>(i & 0xFF);
    d[3] = static_cast<std::byte>(i >> 8);
    d[32] = static_cast<std::byte>(i & 0xFF);
    return d;
}

std::uint16_t rid_of(const std::vector<std::byte>& d) {
    return static_cast<std::uint16_t>(std::to_integer<int>(d[2]) | std::to_integer<int>(d[3]) << 8);
}

FaultConfig parse(std::initializer_list<std::pair<const char*, const char*>> options) {
    FaultConfig config;
    for (const auto& [name, value] : options) {
        const auto r = apply_option(config, name, value);
        EXPECT_TRUE(r.ok()) << name << " " << value << ": " << (r.ok() ? "" : r.error());
    }
    return config;
}

// Runs `n` datagrams through a model; returns every emission, in order, then the flush.
std::vector<Emission> run(FaultModel& model, int n) {
    std::vector<Emission> all;
    for (int i = 0; i < n; ++i) {
        for (auto& e : model.on_datagram(datagram(static_cast<std::uint16_t>(i)))) {
            all.push_back(std::move(e));
        }
    }
    for (auto& e : model.flush()) all.push_back(std::move(e));
    return all;
}

TEST(FaultOptions, ParsesEveryOption) {
    const auto c = parse({{"seed", "42"},
                          {"loss", "0.1"},
                          {"loss-burst", "3"},
                          {"delay", "250"},
                          {"jitter", "0.2:40"},
                          {"duplicate", "0.05"},
                          {"reorder", "0.5"},
                          {"truncate", "0.3:20"},
                          {"corrupt-byte", "0.4"},
                          {"corrupt-bit", "1:9"},
                          {"corrupt-field", "0.25:exchange"}});
    EXPECT_EQ(c.seed, 42u);
    EXPECT_DOUBLE_EQ(c.loss, 0.1);
    EXPECT_EQ(c.loss_burst, 3u);
    EXPECT_EQ(c.delay.count(), 250);
    EXPECT_DOUBLE_EQ(c.jitter, 0.2);
    EXPECT_EQ(c.jitter_delay.count(), 40);
    EXPECT_DOUBLE_EQ(c.duplicate, 0.05);
    EXPECT_DOUBLE_EQ(c.reorder, 0.5);
    EXPECT_DOUBLE_EQ(c.truncate, 0.3);
    EXPECT_EQ(c.truncate_length, 20u);
    EXPECT_DOUBLE_EQ(c.corrupt_byte, 0.4);
    EXPECT_FALSE(c.corrupt_byte_offset.has_value());
    EXPECT_EQ(c.corrupt_bit_offset, 9u);
    EXPECT_EQ(c.field, HeaderField::exchange);
    EXPECT_DOUBLE_EQ(c.probability(Fault::delay), 1.0);
}

TEST(FaultOptions, RejectsBadValuesWithTheOptionName) {
    FaultConfig c;
    for (const auto& [name, value] :
         std::vector<std::pair<const char*, const char*>>{{"loss", "1.5"},
                                                          {"loss", "-0.1"},
                                                          {"loss", "x"},
                                                          {"loss-burst", "0"},
                                                          {"jitter", "0.5"},
                                                          {"corrupt-field", "0.5"},
                                                          {"corrupt-field", "0.5:crc"},
                                                          {"corrupt-byte", "0.5:x"},
                                                          {"seed", "-1"},
                                                          {"nonsense", "1"}}) {
        const auto r = apply_option(c, name, value);
        ASSERT_FALSE(r.ok()) << name << " " << value;
        EXPECT_NE(r.error().find(name), std::string::npos) << r.error();
    }
}

TEST(FaultModel, NoFaultsForwardsEverythingUnchanged) {
    FaultModel model(FaultConfig{});
    const auto out = run(model, 100);
    ASSERT_EQ(out.size(), 100u);
    for (int i = 0; i < 100; ++i) {
        EXPECT_EQ(out[i].bytes, datagram(static_cast<std::uint16_t>(i)));
        EXPECT_EQ(out[i].delay.count(), 0);
    }
    EXPECT_EQ(model.counters().in, 100u);
    EXPECT_EQ(model.counters().out, 100u);
}

TEST(FaultModel, SameSeedSameDecisionsOtherSeedOtherDecisions) {
    const auto options = {std::pair{"loss", "0.2"}, std::pair{"duplicate", "0.2"},
                          std::pair{"reorder", "0.2"}, std::pair{"corrupt-byte", "0.2"},
                          std::pair{"truncate", "0.1"}};
    auto c = parse(options);
    FaultModel a(c);
    FaultModel b(c);
    c.seed = 2;
    FaultModel other(c);
    const auto out_a = run(a, 500);
    const auto out_b = run(b, 500);
    const auto out_other = run(other, 500);
    ASSERT_EQ(out_a.size(), out_b.size());
    for (std::size_t i = 0; i < out_a.size(); ++i) EXPECT_EQ(out_a[i].bytes, out_b[i].bytes);
    bool differs = out_a.size() != out_other.size();
    for (std::size_t i = 0; !differs && i < out_a.size(); ++i) {
        differs = out_a[i].bytes != out_other[i].bytes;
    }
    EXPECT_TRUE(differs);
}

TEST(FaultModel, EnablingAnotherFaultDoesNotChangeLossDecisions) {
    auto loss_only = parse({{"loss", "0.3"}});
    auto with_truncation = parse({{"loss", "0.3"}, {"truncate", "0.5"}});
    FaultModel a(loss_only);
    FaultModel b(with_truncation);
    const auto out_a = run(a, 300);
    const auto out_b = run(b, 300);
    ASSERT_EQ(out_a.size(), out_b.size());
    EXPECT_EQ(a.counters().of(Fault::loss), b.counters().of(Fault::loss));
    // The same datagrams went through: compare those the truncation left whole.
    int whole = 0;
    for (std::size_t i = 0; i < out_a.size(); ++i) {
        if (out_b[i].bytes.size() != out_a[i].bytes.size()) continue;
        EXPECT_EQ(out_a[i].bytes, out_b[i].bytes);
        ++whole;
    }
    EXPECT_GT(whole, 50);
}

TEST(FaultModel, LossRateMatchesProbabilityAndBurstsDropInARow) {
    FaultModel model(parse({{"loss", "0.1"}, {"seed", "7"}}));
    run(model, 10000);
    const auto lost = model.counters().of(Fault::loss);
    EXPECT_NEAR(static_cast<double>(lost) / 10000, 0.1, 0.015);
    EXPECT_EQ(model.counters().out, 10000 - lost);

    FaultModel bursty(parse({{"loss", "0.05"}, {"loss-burst", "4"}, {"seed", "7"}}));
    const auto out = run(bursty, 2000);
    // Every gap in the forwarded request ids is a multiple of 4 (bursts may touch).
    for (std::size_t i = 1; i < out.size(); ++i) {
        const int gap = rid_of(out[i].bytes) - rid_of(out[i - 1].bytes) - 1;
        EXPECT_EQ(gap % 4, 0) << "after rid " << rid_of(out[i - 1].bytes);
    }
    EXPECT_EQ(bursty.counters().of(Fault::loss) % 4, 0u);
}

TEST(FaultModel, DuplicateSendsTheSameBytesTwice) {
    FaultModel model(parse({{"duplicate", "1"}}));
    const auto out = model.on_datagram(datagram(5));
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0].bytes, datagram(5));
    EXPECT_EQ(out[1].bytes, datagram(5));
    EXPECT_EQ(model.counters().of(Fault::duplicate), 1u);
}

TEST(FaultModel, ReorderHoldsOneAndSendsItAfterTheNext) {
    FaultModel model(parse({{"reorder", "1"}}));
    EXPECT_TRUE(model.on_datagram(datagram(1)).empty());
    EXPECT_TRUE(model.holding());
    const auto out = model.on_datagram(datagram(2));
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(rid_of(out[0].bytes), 2);
    EXPECT_EQ(rid_of(out[1].bytes), 1);
    EXPECT_EQ(model.counters().of(Fault::reorder), 1u);
    // Held again; flushed at the end without counting as reordered.
    EXPECT_TRUE(model.on_datagram(datagram(3)).empty());
    const auto flushed = model.flush();
    ASSERT_EQ(flushed.size(), 1u);
    EXPECT_EQ(rid_of(flushed[0].bytes), 3);
    EXPECT_EQ(model.counters().of(Fault::reorder), 1u);
    EXPECT_EQ(model.counters().out, 3u);
}

TEST(FaultModel, DelayAppliesToEveryDatagramAndJitterToSome) {
    FaultModel model(parse({{"delay", "100"}, {"jitter", "0.5:50"}}));
    const auto out = run(model, 1000);
    int jittered = 0;
    for (const auto& e : out) {
        ASSERT_TRUE(e.delay.count() == 100 || e.delay.count() == 150);
        jittered += e.delay.count() == 150;
    }
    EXPECT_EQ(static_cast<std::uint64_t>(jittered), model.counters().of(Fault::jitter));
    EXPECT_NEAR(jittered / 1000.0, 0.5, 0.06);
    EXPECT_EQ(model.counters().of(Fault::delay), 1000u);
}

TEST(FaultModel, TruncateCutsToTheGivenOrARandomShorterLength) {
    FaultModel fixed(parse({{"truncate", "1:20"}}));
    EXPECT_EQ(fixed.on_datagram(datagram(1))[0].bytes.size(), 20u);
    FaultModel out_of_range(parse({{"truncate", "1:4000"}}));
    FaultModel random(parse({{"truncate", "1"}}));
    for (int i = 0; i < 200; ++i) {
        EXPECT_LT(out_of_range.on_datagram(datagram(1))[0].bytes.size(), 40u);
        EXPECT_LT(random.on_datagram(datagram(1))[0].bytes.size(), 40u);
    }
    EXPECT_EQ(random.counters().of(Fault::truncate), 200u);
}

TEST(FaultModel, CorruptByteAndBitChangeExactlyTheChosenPlace) {
    FaultModel byte(parse({{"corrupt-byte", "1:33"}}));
    const auto b = byte.on_datagram(datagram(1))[0].bytes;
    for (std::size_t i = 0; i < b.size(); ++i) {
        if (i == 33) {
            EXPECT_NE(b[i], std::byte{0});
        } else {
            EXPECT_EQ(b[i], datagram(1)[i]) << i;
        }
    }
    FaultModel bit(parse({{"corrupt-bit", "1:258"}}));  // byte 32, bit 2
    const auto c = bit.on_datagram(datagram(1))[0].bytes;
    EXPECT_EQ(c[32], datagram(1)[32] ^ std::byte{0x04});
    // Out of range: a random place, still exactly one bit.
    FaultModel random_bit(parse({{"corrupt-bit", "1:99999"}}));
    for (int i = 0; i < 50; ++i) {
        const auto d = random_bit.on_datagram(datagram(1))[0].bytes;
        int flipped = 0;
        for (std::size_t k = 0; k < d.size(); ++k) {
            flipped += __builtin_popcount(std::to_integer<unsigned>(d[k] ^ datagram(1)[k]));
        }
        EXPECT_EQ(flipped, 1);
    }
}

TEST(FaultModel, CorruptFieldAlwaysChangesOnlyThatField) {
    struct Case {
        const char* name;
        std::size_t offset;
        std::size_t size;
    };
    for (const auto& [name, offset, size] : std::vector<Case>{{"type", 0, 1},
                                                              {"version", 1, 1},
                                                              {"rid", 2, 2},
                                                              {"producer", 4, 4},
                                                              {"exchange", 8, 4},
                                                              {"time", 12, 4},
                                                              {"status", 20, 4},
                                                              {"signature", 24, 4},
                                                              {"reserved", 28, 4}}) {
        FaultModel model(parse({{"corrupt-field", (std::string("1:") + name).c_str()}}));
        for (int i = 0; i < 100; ++i) {
            const auto original = datagram(static_cast<std::uint16_t>(i));
            const auto d = model.on_datagram(original)[0].bytes;
            bool field_changed = false;
            for (std::size_t k = 0; k < d.size(); ++k) {
                if (k >= offset && k < offset + size) {
                    field_changed |= d[k] != original[k];
                } else {
                    EXPECT_EQ(d[k], original[k]) << name << " byte " << k;
                }
            }
            EXPECT_TRUE(field_changed) << name;
        }
        EXPECT_EQ(model.counters().of(Fault::corrupt_field), 100u);
    }
    // A datagram too short for the field passes unchanged and is not counted.
    FaultModel model(parse({{"corrupt-field", "1:reserved"}}));
    const std::vector<std::byte> tiny(10, std::byte{1});
    EXPECT_EQ(model.on_datagram(tiny)[0].bytes, tiny);
    EXPECT_EQ(model.counters().of(Fault::corrupt_field), 0u);
}

TEST(FaultReport, ListsEveryFaultWithProbabilityAndAffectedCount) {
    FaultModel model(parse({{"loss", "0.5"}, {"seed", "3"}}));
    run(model, 100);
    const auto text = format_report(model, 1.5);
    EXPECT_NE(text.find("datagrams in: 100, out: " + std::to_string(model.counters().out)),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("loss"), std::string::npos);
    EXPECT_NE(text.find("0.5000"), std::string::npos);
    EXPECT_NE(text.find("corrupt_field"), std::string::npos);
    const auto json = format_report_json(model, 1.5);
    EXPECT_NE(json.find(R"("in":100)"), std::string::npos) << json;
    EXPECT_NE(json.find(R"("loss":{"probability":0.5,"affected":)" +
                        std::to_string(model.counters().of(Fault::loss)) + "}"),
              std::string::npos)
        << json;
}

}  // namespace
}  // namespace eip2mqtt::fault_injector
