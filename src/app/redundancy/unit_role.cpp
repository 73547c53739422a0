#include "eip2mqtt/app/redundancy/unit_role.hpp"

namespace eip2mqtt::app::redundancy {

UnitRole& always_leads() {
    static AlwaysLeads role;
    return role;
}

}  // namespace eip2mqtt::app::redundancy
