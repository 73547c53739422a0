#pragma once
// A role (app/redundancy/unit_role.hpp) the test switches by hand; it counts how often it is
// asked whether to produce, follows the other unit's request ids while it does not lead, and
// hands each accepted write's answer to `on_answer` (unset: answered at once); it applies every
// write. One thread.

#include <functional>
#include <vector>

#include "eip2mqtt/app/redundancy/unit_role.hpp"

namespace eip2mqtt::test {

class SwitchedRole final : public app::redundancy::UnitRole {
public:
    using OnAnswer =
        std::function<void(const app::ExchangeProducer& producer, std::uint64_t write_id,
                           const app::WriteReply& reply, std::function<void()> answer)>;

    bool leads() const override { return leading; }
    bool may_produce(core::MonoTime) const override {
        ++asked;
        return leading;
    }
    bool hears_produced() const override { return hears; }
    bool follows_produced(core::MonoTime) const override { return !leading; }
    void image_changed(const app::ExchangeProducer& producer) override {
        changed.push_back(&producer);
    }
    void answer_write(const app::ExchangeProducer& producer, std::uint64_t write_id,
                      const app::WriteReply& reply, std::function<void()> answer) override {
        if (!on_answer) return answer();
        on_answer(producer, write_id, reply, std::move(answer));
    }
    app::redundancy::WriteTurn admit_write(app::WriteRequest&,
                                           core::write::WriteCounters&) override {
        return app::redundancy::WriteTurn::apply;
    }
    app::redundancy::WriteTurn settle_write(const app::WriteRequest&,
                                            core::write::WriteCounters&) override {
        return app::redundancy::WriteTurn::apply;
    }
    core::write::WriteRejection refusal() const override { return {}; }

    bool leading = false;
    bool hears = true;  ///< hears_produced()
    mutable int asked = 0;
    std::vector<const app::ExchangeProducer*> changed;
    OnAnswer on_answer;
};

}  // namespace eip2mqtt::test
