#pragma once
// A role (app/redundancy/unit_role.hpp) the test switches by hand. One thread.

#include "eip2mqtt/app/redundancy/unit_role.hpp"

namespace eip2mqtt::test {

class SwitchedRole final : public app::redundancy::UnitRole {
public:
    bool leads() const override { return leading; }

    bool leading = false;
};

}  // namespace eip2mqtt::test
