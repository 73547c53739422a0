#include "eip2mqtt/app/redundancy/unit_role.hpp"

namespace eip2mqtt::app::redundancy {

const UnitRole& always_leads() {
    static const AlwaysLeads role;
    return role;
}

}  // namespace eip2mqtt::app::redundancy
