#pragma once
// A role (app/redundancy/unit_role.hpp) the test switches by hand; it counts how often it is
// asked whether to produce. One thread.

#include "eip2mqtt/app/redundancy/unit_role.hpp"

namespace eip2mqtt::test {

class SwitchedRole final : public app::redundancy::UnitRole {
public:
    bool leads() const override { return leading; }
    bool may_produce(core::MonoTime) const override {
        ++asked;
        return leading;
    }

    bool leading = false;
    mutable int asked = 0;
};

}  // namespace eip2mqtt::test
