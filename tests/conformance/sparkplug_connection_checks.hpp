#pragma once
/// The named checks of the Sparkplug conformance suite, each with the alteration that breaks
/// it (break_...), in files by what they read: the CONNECT and its will
/// (sparkplug_connection_checks.cpp), the session on a connection (sparkplug_session_checks),
/// the primary host (sparkplug_host_checks), payload contents (sparkplug_metric_checks), DATA
/// against births (sparkplug_data_checks, sparkplug_birth_checks).

#include "tests/conformance/sparkplug_requirements.hpp"

namespace eip2mqtt::test::conformance::checks {

// The CONNECT and its will.
Verdict will_registered(const NodeView& view);
void break_will_registered(NodeView& view);
Verdict will_is_ndeath(const NodeView& view);
void break_will_topic(NodeView& view);
void break_will_payload(NodeView& view);
Verdict will_qos1_not_retained(const NodeView& view);
void break_will_qos(NodeView& view);
void break_will_retain(NodeView& view);
Verdict bd_seq_counts_connects(const NodeView& view);
void break_bd_seq_counts(NodeView& view);
Verdict nbirth_bd_seq_is_the_wills(const NodeView& view);
void break_nbirth_bd_seq(NodeView& view);

// The session on a connection.
Verdict subscribes_ncmd(const NodeView& view);
void break_subscribes_ncmd(NodeView& view);
Verdict subscribes_dcmd(const NodeView& view);
void break_subscribes_dcmd(NodeView& view);
Verdict births_after_connack(const NodeView& view);
void break_births_after_connack(NodeView& view);
Verdict no_device_before_nbirth(const NodeView& view);
void break_no_device_before_nbirth(NodeView& view);
Verdict ndeath_before_disconnect(const NodeView& view);
void break_ndeath_before_disconnect(NodeView& view);
Verdict disconnect_with_will_reason(const NodeView& view);
void break_disconnect_with_will_reason(NodeView& view);
Verdict one_broker_at_a_time(const NodeView& view);
void break_one_broker_at_a_time(NodeView& view);

// The primary host. Which property of the STATE that let births start is judged.
enum class HostRule { present, id, online, timestamp };
Verdict births_wait_for_the_host(const NodeView& view, const HostRule& rule);
void break_births_wait_for_the_host(NodeView& view, const HostRule& rule);
Verdict offline_ends_the_session(const NodeView& view);
void break_offline_ends_the_session(NodeView& view);
Verdict older_offline_keeps_the_session(const NodeView& view);
void break_older_offline_keeps_the_session(NodeView& view);
Verdict offline_walks_to_the_next_broker(const NodeView& view);
void break_offline_walks(NodeView& view);

// Payload contents.
Verdict rebirth_metric(const NodeView& view);
void break_rebirth_metric(NodeView& view);
Verdict rebirth_without_alias(const NodeView& view);
void break_rebirth_without_alias(NodeView& view);
Verdict births_name_type_and_value(const NodeView& view);
void break_births_value(NodeView& view);
void break_births_datatype(NodeView& view);
Verdict birth_aliases(const NodeView& view);
void break_birth_aliases(NodeView& view);
Verdict data_by_alias_only(const NodeView& view);
void break_data_by_alias_only(NodeView& view);
Verdict named_or_aliased(const NodeView& view);
void break_named_or_aliased(NodeView& view);
Verdict metric_timestamps(const NodeView& view);
void break_metric_timestamps(NodeView& view);
Verdict metric_timestamps_utc(const NodeView& view);
void break_metric_timestamps_utc(NodeView& view);
Verdict datatypes_valid(const NodeView& view);
void break_datatypes_valid(NodeView& view);
Verdict properties_well_formed(const NodeView& view);
void break_properties(NodeView& view);
Verdict no_dataset_or_template(const NodeView& view);
void break_no_dataset_or_template(NodeView& view);
Verdict no_quality_or_a_valid_one(const NodeView& view);
void break_quality(NodeView& view);

// DATA against births, and the node's whole run.
Verdict data_announced_by_birth(const NodeView& view);
void break_data_announced(NodeView& view);
Verdict data_carries_changes(const NodeView& view);
void break_data_carries_changes(NodeView& view);
Verdict data_in_time_order(const NodeView& view);
void break_data_in_time_order(NodeView& view);
Verdict ndeath_is_bd_seq_alone(const NodeView& view);
void break_ndeath_is_bd_seq_alone(NodeView& view);
void break_ndeath_bd_seq(NodeView& view);
Verdict metric_names_apart_in_case(const NodeView& view);
void break_metric_names_apart_in_case(NodeView& view);
Verdict ids_are_topic_elements(const NodeView& view);
void break_ids_are_topic_elements(NodeView& view);
Verdict aliases_unique_in_the_node(const NodeView& view);
void break_aliases_unique(NodeView& view);
Verdict device_ids_unique(const NodeView& view);
void break_device_ids_unique(NodeView& view);
Verdict device_data_after_its_birth(const NodeView& view);
void break_device_data_after_its_birth(NodeView& view);
Verdict births_complete_before_data(const NodeView& view);
void break_births_complete_before_data(NodeView& view);
Verdict rebirth_request_stops_data(const NodeView& view);
void break_rebirth_request_stops_data(NodeView& view);
Verdict silent_device_dies_and_returns(const NodeView& view);
void break_silent_device_dies(NodeView& view);

}  // namespace eip2mqtt::test::conformance::checks
