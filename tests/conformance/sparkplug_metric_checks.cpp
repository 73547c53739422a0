// The checks of what the node's payloads hold: bdSeq and Rebirth in NBIRTH, every birth
// metric named, typed and valued, aliases, timestamps, datatypes, properties, and DATA that
// carries only what its birth announced and what changed.

#include <algorithm>
#include <map>
#include <set>

#include "tests/conformance/sparkplug_checks.hpp"
#include "tests/conformance/sparkplug_connection_checks.hpp"

namespace eip2mqtt::test::conformance::checks {
namespace {

constexpr std::string_view rebirth = "Node Control/Rebirth";
constexpr std::uint32_t boolean = 11, data_set = 16, templated = 19;

/// Calls `f` on each metric of each payload of `types` the node sent.
Verdict each_metric(
    const NodeView& view, std::initializer_list<std::string_view> types,
    const std::function<Verdict(const SparkplugPayload::Metric&, std::string_view type)>& f) {
    return each_sent(view, "", [&](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto t = type_of(view, c.packets[i]);
        if (std::find(types.begin(), types.end(), t) == types.end()) return std::nullopt;
        if (!c.packets[i].payload) return std::nullopt;
        for (const auto& m : c.packets[i].payload->metrics()) {
            if (auto v = f(m, t)) return where(c, i) + ": metric " + m.name() + " " + *v;
        }
        return std::nullopt;
    });
}

SparkplugPayload::Metric& first_metric(NodeView& view, std::string_view type) {
    auto& payload = *first_sent(view, type).payload;
    return *payload.mutable_metrics(payload.metrics_size() - 1);
}

}  // namespace

Verdict rebirth_metric(const NodeView& view) {
    return each_sent(view, "NBIRTH", [](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto* m = metric_named(*c.packets[i].payload, std::string(rebirth));
        if (!m) return where(c, i) + ": no Node Control/Rebirth";
        if (m->datatype() != boolean || !m->has_boolean_value() || m->boolean_value()) {
            return where(c, i) + ": Node Control/Rebirth is not Boolean false";
        }
        return std::nullopt;
    });
}
void break_rebirth_metric(NodeView& view) {
    for (auto& m : *first_sent(view, "NBIRTH").payload->mutable_metrics()) {
        if (m.name() == rebirth) m.set_boolean_value(true);
    }
}

Verdict rebirth_without_alias(const NodeView& view) {
    return each_sent(view, "NBIRTH", [](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto* m = metric_named(*c.packets[i].payload, std::string(rebirth));
        if (m && m->has_alias()) return where(c, i) + ": Node Control/Rebirth has an alias";
        return std::nullopt;
    });
}
void break_rebirth_without_alias(NodeView& view) {
    for (auto& m : *first_sent(view, "NBIRTH").payload->mutable_metrics()) {
        if (m.name() == rebirth) m.set_alias(1);
    }
}

Verdict births_name_type_and_value(const NodeView& view) {
    return each_metric(view, {"NBIRTH", "DBIRTH"}, [](auto& m, auto) -> Verdict {
        if (m.name().empty()) return "without a name";
        if (!m.has_datatype()) return "without a datatype";
        const bool valued = m.value_case() != SparkplugPayload::Metric::VALUE_NOT_SET;
        if (m.is_null() == valued) return m.is_null() ? "null with a value" : "without a value";
        return std::nullopt;
    });
}
void break_births_value(NodeView& view) { first_metric(view, "DBIRTH").clear_value(); }
void break_births_datatype(NodeView& view) { first_metric(view, "NBIRTH").clear_datatype(); }

Verdict birth_aliases(const NodeView& view) {
    return each_metric(view, {"NBIRTH", "DBIRTH"}, [](auto& m, auto) -> Verdict {
        if (m.name() != rebirth && !m.has_alias()) return "without an alias";
        return std::nullopt;
    });
}
void break_birth_aliases(NodeView& view) { first_metric(view, "DBIRTH").clear_alias(); }

Verdict data_by_alias_only(const NodeView& view) {
    return each_metric(view, {"NDATA", "DDATA"}, [](auto& m, auto) -> Verdict {
        if (!m.has_alias()) return "without an alias";
        if (!m.name().empty()) return "with its name";
        return std::nullopt;
    });
}
void break_data_by_alias_only(NodeView& view) { first_metric(view, "DDATA").set_name("A"); }

Verdict named_or_aliased(const NodeView& view) {
    return each_metric(view, {"NBIRTH", "DBIRTH", "NDATA", "DDATA", "NDEATH"},
                       [](auto& m, auto) -> Verdict {
                           if (m.name().empty() && !m.has_alias()) return "nameless";
                           return std::nullopt;
                       });
}
void break_named_or_aliased(NodeView& view) {
    auto& m = first_metric(view, "DDATA");
    m.clear_alias();
    m.clear_name();
}

Verdict metric_timestamps(const NodeView& view) {
    return each_metric(view, {"NBIRTH", "DBIRTH", "NDATA", "DDATA"}, [&](auto& m, auto) -> Verdict {
        if (!m.has_timestamp()) return "without a timestamp";
        return std::nullopt;
    });
}
void break_metric_timestamps(NodeView& view) { first_metric(view, "NDATA").clear_timestamp(); }

Verdict metric_timestamps_utc(const NodeView& view) {
    return each_metric(view, {"NBIRTH", "DBIRTH", "NDATA", "DDATA"}, [&](auto& m, auto) -> Verdict {
        const auto ms = static_cast<std::int64_t>(m.timestamp());
        // A tag's timestamp may be its datagram's, taken before the run's own first instant
        // by at most the harness's set-up; never hours off as a local time would be.
        if (ms < view.wall_from_ms - 60'000 || ms > view.wall_to_ms) {
            return "timestamp " + std::to_string(ms) + " outside the run's UTC span";
        }
        return std::nullopt;
    });
}
void break_metric_timestamps_utc(NodeView& view) {
    auto& m = first_metric(view, "DDATA");
    m.set_timestamp(m.timestamp() + 3'600'000);
}

Verdict datatypes_valid(const NodeView& view) {
    return each_metric(view, {"NBIRTH", "DBIRTH", "NDATA", "DDATA", "NDEATH"},
                       [](auto& m, auto) -> Verdict {
                           if (m.has_datatype() && (m.datatype() < 1 || m.datatype() > 21)) {
                               return "datatype " + std::to_string(m.datatype());
                           }
                           return std::nullopt;
                       });
}
void break_datatypes_valid(NodeView& view) { first_metric(view, "DBIRTH").set_datatype(99); }

Verdict properties_well_formed(const NodeView& view) {
    bool any = false;
    const auto verdict = each_metric(view, {"DBIRTH"}, [&](auto& m, auto) -> Verdict {
        if (!m.has_properties()) return std::nullopt;
        any = true;
        const auto& p = m.properties();
        if (p.keys_size() != p.values_size()) return "properties: keys and values differ";
        for (const auto& v : p.values()) {
            if (!v.has_type() || v.type() < 1 || v.type() > 21) return "a property without type";
        }
        return std::nullopt;
    });
    if (verdict) return verdict;
    return any ? Verdict{} : Verdict{"no DBIRTH metric had properties in the run"};
}
void break_properties(NodeView& view) {
    auto& payload = *first_sent(view, "DBIRTH").payload;
    for (auto& m : *payload.mutable_metrics()) {
        if (m.has_properties()) m.mutable_properties()->add_keys("orphan");
    }
}

Verdict no_dataset_or_template(const NodeView& view) {
    return each_metric(view, {"NBIRTH", "DBIRTH", "NDATA", "DDATA"}, [](auto& m, auto) -> Verdict {
        if (m.datatype() == data_set || m.datatype() == templated) return "a DataSet or Template";
        for (const auto& v : m.properties().values()) {
            if (v.type() == data_set || v.type() == templated) return "a DataSet property";
        }
        return std::nullopt;
    });
}
void break_no_dataset_or_template(NodeView& view) {
    first_metric(view, "NBIRTH").set_datatype(templated);
}

Verdict no_quality_or_a_valid_one(const NodeView& view) {
    return each_metric(view, {"DBIRTH", "DDATA"}, [](auto& m, auto) -> Verdict {
        const auto& p = m.properties();
        for (int k = 0; k < p.keys_size() && k < p.values_size(); ++k) {
            if (p.keys(k) != "Quality") continue;
            const auto& v = p.values(k);
            const auto q = static_cast<std::int32_t>(v.int_value());
            if (v.type() != 3 || (q != 0 && q != 192 && q != 500))
                return "Quality " + std::to_string(q);
        }
        return std::nullopt;
    });
}
void break_quality(NodeView& view) {
    auto& m = first_metric(view, "DBIRTH");
    m.mutable_properties()->add_keys("Quality");
    auto& v = *m.mutable_properties()->add_values();
    v.set_type(3);
    v.set_int_value(7);
}

}  // namespace eip2mqtt::test::conformance::checks
