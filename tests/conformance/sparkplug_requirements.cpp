// Each edge-node tck-id of the Sparkplug B 3.0 specification and the check that judges it.
// Several ids say one thing in different chapters (the NBIRTH's QoS in chapters 4, 5 and 6):
// they share a check. The ids not judged are in sparkplug_not_judged.cpp.

#include "tests/conformance/sparkplug_requirements.hpp"

#include <vector>

#include "tests/conformance/sparkplug_checks.hpp"
#include "tests/conformance/sparkplug_connection_checks.hpp"

namespace eip2mqtt::test::conformance {
namespace {

using namespace checks;

Requirement named(std::string_view id, Verdict (*check)(const NodeView&),
                  void (*break_it)(NodeView&), Run run = Run::mqtt5) {
    return {id, run, check, break_it};
}

Requirement host(std::string_view id, HostRule rule) {
    return {id, Run::mqtt5, [rule](const NodeView& v) { return births_wait_for_the_host(v, rule); },
            [rule](NodeView& v) { break_births_wait_for_the_host(v, rule); }};
}

std::vector<Requirement> topics_chapter() {
    return {
        named("topic-structure", ids_are_topic_elements, break_ids_are_topic_elements),
        named("topic-structure-namespace-a", ids_are_topic_elements, break_ids_are_topic_elements),
        named("topic-structure-namespace-valid-group-id", ids_are_topic_elements,
              break_ids_are_topic_elements),
        named("topic-structure-namespace-valid-edge-node-id", ids_are_topic_elements,
              break_ids_are_topic_elements),
        named("topic-structure-namespace-valid-device-id", ids_are_topic_elements,
              break_ids_are_topic_elements),
        named("topic-structure-namespace-unique-device-id", device_ids_unique,
              break_device_ids_unique),
        topic_of_type("topic-structure-namespace-device-id-associated-message-types", "DDATA"),
        topic_of_type("topic-structure-namespace-device-id-non-associated-message-types", "NBIRTH"),
        topic_of_type("topics-nbirth-topic", "NBIRTH"),
        qos0_not_retained("topics-nbirth-mqtt", "NBIRTH"),
        has_seq("topics-nbirth-seq-num", "NBIRTH"),
        has_timestamp("topics-nbirth-timestamp", "NBIRTH"),
        named("topics-nbirth-metric-reqs", data_announced_by_birth, break_data_announced),
        named("topics-nbirth-metrics", births_name_type_and_value, break_births_value),
        named("topics-nbirth-templates", no_dataset_or_template, break_no_dataset_or_template),
        named("topics-nbirth-bdseq-included", nbirth_bd_seq_is_the_wills, break_nbirth_bd_seq),
        named("topics-nbirth-bdseq-matching", nbirth_bd_seq_is_the_wills, break_nbirth_bd_seq),
        named("topics-nbirth-bdseq-increment", bd_seq_counts_connects, break_bd_seq_counts),
        named("topics-nbirth-rebirth-metric", rebirth_metric, break_rebirth_metric),
        topic_of_type("topics-ndata-topic", "NDATA"),
        qos0_not_retained("topics-ndata-mqtt", "NDATA"),
        seq_one_more("topics-ndata-seq-num", "NDATA"),
        has_timestamp("topics-ndata-timestamp", "NDATA"),
        named("topics-ndata-payload", data_carries_changes, break_data_carries_changes),
        topic_of_type("topics-ndeath-topic", "NDEATH"),
        named("topics-ndeath-payload", ndeath_is_bd_seq_alone, break_ndeath_is_bd_seq_alone),
        has_seq("topics-ndeath-seq", "NDEATH"),
        topic_of_type("topics-dbirth-topic", "DBIRTH"),
        qos0_not_retained("topics-dbirth-mqtt", "DBIRTH"),
        seq_one_more("topics-dbirth-seq", "DBIRTH"),
        has_timestamp("topics-dbirth-timestamp", "DBIRTH"),
        named("topics-dbirth-metric-reqs", data_announced_by_birth, break_data_announced),
        named("topics-dbirth-metrics", births_name_type_and_value, break_births_value),
        topic_of_type("topics-ddata-topic", "DDATA"),
        qos0_not_retained("topics-ddata-mqtt", "DDATA"),
        seq_one_more("topics-ddata-seq-num", "DDATA"),
        has_timestamp("topics-ddata-timestamp", "DDATA"),
        named("topics-ddata-payload", data_carries_changes, break_data_carries_changes),
        topic_of_type("topics-ddeath-topic", "DDEATH"),
        qos0_not_retained("topics-ddeath-mqtt", "DDEATH"),
        seq_one_more("topics-ddeath-seq-num", "DDEATH"),
    };
}

std::vector<Requirement> session_chapter() {
    return {
        named("case-sensitivity-metric-names", metric_names_apart_in_case,
              break_metric_names_apart_in_case),
        named("message-flow-edge-node-ncmd-subscribe", subscribes_ncmd, break_subscribes_ncmd),
        named("message-flow-edge-node-birth-publish-connect", births_after_connack,
              break_births_after_connack),
        named("message-flow-edge-node-birth-publish-will-message", will_registered,
              break_will_registered),
        named("message-flow-edge-node-birth-publish-will-message-topic", will_is_ndeath,
              break_will_topic),
        named("message-flow-edge-node-birth-publish-will-message-payload", will_is_ndeath,
              break_will_payload),
        named("message-flow-edge-node-birth-publish-will-message-payload-bdSeq",
              bd_seq_counts_connects, break_bd_seq_counts),
        named("message-flow-edge-node-birth-publish-will-message-qos", will_qos1_not_retained,
              break_will_qos),
        named("message-flow-edge-node-birth-publish-will-message-will-retained",
              will_qos1_not_retained, break_will_retain),
        host("message-flow-edge-node-birth-publish-phid-wait", HostRule::present),
        host("message-flow-edge-node-birth-publish-phid-wait-id", HostRule::id),
        host("message-flow-edge-node-birth-publish-phid-wait-online", HostRule::online),
        host("message-flow-edge-node-birth-publish-phid-wait-timestamp", HostRule::timestamp),
        topic_of_type("message-flow-edge-node-birth-publish-nbirth-topic", "NBIRTH"),
        decodes("message-flow-edge-node-birth-publish-nbirth-payload", "NBIRTH"),
        named("message-flow-edge-node-birth-publish-nbirth-payload-bdSeq",
              nbirth_bd_seq_is_the_wills, break_nbirth_bd_seq),
        qos0_not_retained("message-flow-edge-node-birth-publish-nbirth-qos", "NBIRTH"),
        qos0_not_retained("message-flow-edge-node-birth-publish-nbirth-retained", "NBIRTH"),
        has_seq("message-flow-edge-node-birth-publish-nbirth-payload-seq", "NBIRTH"),
        named("message-flow-edge-node-birth-publish-phid-offline", offline_ends_the_session,
              break_offline_ends_the_session),
        named("operational-behavior-edge-node-intentional-disconnect-ndeath",
              ndeath_before_disconnect, break_ndeath_before_disconnect),
        named("operational-behavior-edge-node-termination-host-offline", offline_ends_the_session,
              break_offline_ends_the_session),
        named("operational-behavior-edge-node-termination-host-offline-reconnect",
              offline_walks_to_the_next_broker, break_offline_walks),
        named("operational-behavior-edge-node-termination-host-offline-timestamp",
              older_offline_keeps_the_session, break_older_offline_keeps_the_session),
        named("message-flow-device-dcmd-subscribe", subscribes_dcmd, break_subscribes_dcmd),
        named("message-flow-device-birth-publish-nbirth-wait", no_device_before_nbirth,
              break_no_device_before_nbirth),
        topic_of_type("message-flow-device-birth-publish-dbirth-topic", "DBIRTH"),
        topic_of_type("message-flow-device-birth-publish-dbirth-match-edge-node-topic", "DBIRTH"),
        decodes("message-flow-device-birth-publish-dbirth-payload", "DBIRTH"),
        qos0_not_retained("message-flow-device-birth-publish-dbirth-qos", "DBIRTH"),
        qos0_not_retained("message-flow-device-birth-publish-dbirth-retained", "DBIRTH"),
        seq_one_more("message-flow-device-birth-publish-dbirth-payload-seq", "DBIRTH"),
        named("operational-behavior-device-ddeath", silent_device_dies_and_returns,
              break_silent_device_dies),
        named("operational-behavior-primary-application-state-with-multiple-servers-single-server",
              one_broker_at_a_time, break_one_broker_at_a_time),
        named("operational-behavior-primary-application-state-with-multiple-servers-walk",
              offline_walks_to_the_next_broker, break_offline_walks),
        host("operational-behavior-edge-node-birth-sequence-wait", HostRule::online),
    };
}

std::vector<Requirement> data_and_commands() {
    return {
        named("operational-behavior-data-publish-nbirth", data_announced_by_birth,
              break_data_announced),
        named("operational-behavior-data-publish-nbirth-values", births_name_type_and_value,
              break_births_value),
        named("operational-behavior-data-publish-nbirth-change", data_carries_changes,
              break_data_carries_changes),
        named("operational-behavior-data-publish-nbirth-order", data_in_time_order,
              break_data_in_time_order),
        named("operational-behavior-data-publish-dbirth", data_announced_by_birth,
              break_data_announced),
        named("operational-behavior-data-publish-dbirth-values", births_name_type_and_value,
              break_births_value),
        named("operational-behavior-data-publish-dbirth-change", data_carries_changes,
              break_data_carries_changes),
        named("operational-behavior-data-publish-dbirth-order", data_in_time_order,
              break_data_in_time_order),
        named("operational-behavior-data-commands-rebirth-name", rebirth_metric,
              break_rebirth_metric),
        named("operational-behavior-data-commands-rebirth-name-aliases", rebirth_without_alias,
              break_rebirth_without_alias),
        named("operational-behavior-data-commands-rebirth-datatype", rebirth_metric,
              break_rebirth_metric),
        named("operational-behavior-data-commands-rebirth-value", rebirth_metric,
              break_rebirth_metric),
        named("operational-behavior-data-commands-rebirth-action-1", rebirth_request_stops_data,
              break_rebirth_request_stops_data),
        named("operational-behavior-data-commands-rebirth-action-2", births_complete_before_data,
              break_births_complete_before_data),
        named("operational-behavior-data-commands-rebirth-action-3", nbirth_bd_seq_is_the_wills,
              break_nbirth_bd_seq),
    };
}

std::vector<Requirement> payloads_chapter() {
    return {
        has_timestamp("payloads-timestamp-in-UTC", ""),
        has_seq("payloads-sequence-num-always-included", ""),
        has_seq("payloads-sequence-num-req-nbirth", "NBIRTH"),
        seq_one_more("payloads-sequence-num-incrementing", ""),
        named("payloads-name-requirement", named_or_aliased, break_named_or_aliased),
        named("payloads-alias-uniqueness", aliases_unique_in_the_node, break_aliases_unique),
        named("payloads-alias-birth-requirement", birth_aliases, break_birth_aliases),
        named("payloads-alias-data-cmd-requirement", data_by_alias_only, break_data_by_alias_only),
        named("payloads-name-birth-data-requirement", metric_timestamps, break_metric_timestamps),
        named("payloads-metric-timestamp-in-UTC", metric_timestamps_utc,
              break_metric_timestamps_utc),
        named("payloads-metric-datatype-value-type", datatypes_valid, break_datatypes_valid),
        named("payloads-metric-datatype-value", datatypes_valid, break_datatypes_valid),
        named("payloads-metric-datatype-req", births_name_type_and_value, break_births_datatype),
        named("payloads-propertyset-keys-array-size", properties_well_formed, break_properties),
        named("payloads-propertyset-values-array-size", properties_well_formed, break_properties),
        named("payloads-metric-propertyvalue-type-type", properties_well_formed, break_properties),
        named("payloads-metric-propertyvalue-type-value", properties_well_formed, break_properties),
        named("payloads-metric-propertyvalue-type-req", properties_well_formed, break_properties),
        named("payloads-propertyset-quality-value-type", no_quality_or_a_valid_one, break_quality),
        named("payloads-propertyset-quality-value-value", no_quality_or_a_valid_one, break_quality),
    };
}

std::vector<Requirement> payloads_by_message_type() {
    return {
        has_timestamp("payloads-nbirth-timestamp", "NBIRTH"),
        has_seq("payloads-nbirth-seq", "NBIRTH"),
        named("payloads-nbirth-bdseq", nbirth_bd_seq_is_the_wills, break_nbirth_bd_seq),
        named("payloads-nbirth-bdseq-repeat", nbirth_bd_seq_is_the_wills, break_nbirth_bd_seq),
        named("payloads-nbirth-rebirth-req", rebirth_metric, break_rebirth_metric),
        qos0_not_retained("payloads-nbirth-qos", "NBIRTH"),
        qos0_not_retained("payloads-nbirth-retain", "NBIRTH"),
        has_timestamp("payloads-dbirth-timestamp", "DBIRTH"),
        has_seq("payloads-dbirth-seq", "DBIRTH"),
        seq_one_more("payloads-dbirth-seq-inc", "DBIRTH"),
        named("payloads-dbirth-order", births_complete_before_data,
              break_births_complete_before_data),
        qos0_not_retained("payloads-dbirth-qos", "DBIRTH"),
        qos0_not_retained("payloads-dbirth-retain", "DBIRTH"),
        has_timestamp("payloads-ndata-timestamp", "NDATA"),
        has_seq("payloads-ndata-seq", "NDATA"),
        seq_one_more("payloads-ndata-seq-inc", "NDATA"),
        named("payloads-ndata-order", births_complete_before_data,
              break_births_complete_before_data),
        qos0_not_retained("payloads-ndata-qos", "NDATA"),
        qos0_not_retained("payloads-ndata-retain", "NDATA"),
        has_timestamp("payloads-ddata-timestamp", "DDATA"),
        has_seq("payloads-ddata-seq", "DDATA"),
        seq_one_more("payloads-ddata-seq-inc", "DDATA"),
        named("payloads-ddata-order", device_data_after_its_birth,
              break_device_data_after_its_birth),
        qos0_not_retained("payloads-ddata-qos", "DDATA"),
        qos0_not_retained("payloads-ddata-retain", "DDATA"),
        has_seq("payloads-ndeath-seq", "NDEATH"),
        named("payloads-ndeath-will-message", will_is_ndeath, break_will_topic),
        named("payloads-ndeath-will-message-qos", will_qos1_not_retained, break_will_qos),
        named("payloads-ndeath-will-message-retain", will_qos1_not_retained, break_will_retain),
        named("payloads-ndeath-bdseq", ndeath_is_bd_seq_alone, break_ndeath_bd_seq),
        named("payloads-ndeath-will-message-publisher", ndeath_before_disconnect,
              break_ndeath_before_disconnect),
        named("payloads-ndeath-will-message-publisher-disconnect-mqtt311", ndeath_before_disconnect,
              break_ndeath_before_disconnect, Run::mqtt311),
        named("payloads-ndeath-will-message-publisher-disconnect-mqtt50",
              disconnect_with_will_reason, break_disconnect_with_will_reason),
        has_timestamp("payloads-ddeath-timestamp", "DDEATH"),
        has_seq("payloads-ddeath-seq", "DDEATH"),
        seq_one_more("payloads-ddeath-seq-inc", "DDEATH"),
        seq_one_more("payloads-ddeath-seq-number", "DDEATH"),
    };
}

std::vector<Requirement> all_requirements() {
    std::vector<Requirement> all;
    for (auto part : {topics_chapter(), session_chapter(), data_and_commands(), payloads_chapter(),
                      payloads_by_message_type()}) {
        for (auto& r : part) all.push_back(std::move(r));
    }
    return all;
}

}  // namespace

std::span<const Requirement> edge_node_requirements() {
    static const std::vector<Requirement> all = all_requirements();
    return all;
}

}  // namespace eip2mqtt::test::conformance
