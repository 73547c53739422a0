// The tck-ids of the Sparkplug B 3.0 specification the conformance suite does not judge, each
// with the reason: most are a host's or an MQTT server's; one recommendation is knowingly not
// followed, and says why. docs/sparkplug.md's table shows them (sparkplug_table_test.cpp).

#include <vector>

#include "tests/conformance/sparkplug_requirements.hpp"

namespace eip2mqtt::test::conformance {
namespace {

constexpr std::string_view server_why = "a requirement of the MQTT server, not of an edge node";
constexpr std::string_view server_ids[] = {
    "conformance-mqtt-qos0",
    "conformance-mqtt-qos1",
    "conformance-mqtt-will-messages",
    "conformance-mqtt-retained",
    "conformance-mqtt-aware-basic",
    "conformance-mqtt-aware-store",
    "conformance-mqtt-aware-nbirth-mqtt-topic",
    "conformance-mqtt-aware-nbirth-mqtt-retain",
    "conformance-mqtt-aware-dbirth-mqtt-topic",
    "conformance-mqtt-aware-dbirth-mqtt-retain",
    "conformance-mqtt-aware-ndeath-timestamp",
};

constexpr std::string_view host_why =
    "a requirement of a host application (the suite plays the host)";
constexpr std::string_view host_ids[] = {
    "conformance-primary-host",
    "components-ph-state",
    "host-topic-phid-birth-message",
    "host-topic-phid-birth-qos",
    "host-topic-phid-birth-retain",
    "host-topic-phid-birth-topic",
    "host-topic-phid-birth-sub-required",
    "host-topic-phid-birth-required",
    "host-topic-phid-birth-payload",
    "host-topic-phid-birth-payload-timestamp",
    "host-topic-phid-death-qos",
    "host-topic-phid-death-retain",
    "host-topic-phid-death-topic",
    "host-topic-phid-death-required",
    "host-topic-phid-death-payload",
    "host-topic-phid-death-payload-timestamp-connect",
    "host-topic-phid-death-payload-timestamp-disconnect-clean",
    "host-topic-phid-death-payload-timestamp-disconnect-with-no-disconnect-packet",
    "message-flow-phid-sparkplug-clean-session-311",
    "message-flow-phid-sparkplug-clean-session-50",
    "message-flow-phid-sparkplug-subscription",
    "message-flow-phid-sparkplug-state-publish",
    "message-flow-phid-sparkplug-state-publish-payload",
    "message-flow-phid-sparkplug-state-publish-payload-timestamp",
    "message-flow-hid-sparkplug-state-message-delivered",
    "operational-behavior-edge-node-termination-host-action-ndeath-node-offline",
    "operational-behavior-edge-node-termination-host-action-ndeath-node-tags-stale",
    "operational-behavior-edge-node-termination-host-action-ndeath-devices-offline",
    "operational-behavior-edge-node-termination-host-action-ndeath-devices-tags-stale",
    "operational-behavior-edge-node-termination-host-action-ddeath-devices-offline",
    "operational-behavior-edge-node-termination-host-action-ddeath-devices-tags-stale",
    "operational-behavior-host-reordering-param",
    "operational-behavior-host-reordering-start",
    "operational-behavior-host-reordering-rebirth",
    "operational-behavior-host-reordering-success",
    "operational-behavior-primary-application-state-with-multiple-servers-state-subs",
    "operational-behavior-primary-application-state-with-multiple-servers-state",
    "operational-behavior-host-application-host-id",
    "operational-behavior-host-application-connect-will",
    "operational-behavior-host-application-connect-will-topic",
    "operational-behavior-host-application-connect-will-payload",
    "operational-behavior-host-application-connect-will-qos",
    "operational-behavior-host-application-connect-will-retained",
    "operational-behavior-host-application-connect-birth",
    "operational-behavior-host-application-connect-birth-topic",
    "operational-behavior-host-application-connect-birth-payload",
    "operational-behavior-host-application-connect-birth-qos",
    "operational-behavior-host-application-connect-birth-retained",
    "operational-behavior-host-application-multi-server-timestamp",
    "operational-behavior-host-application-termination",
    "operational-behavior-host-application-death-topic",
    "operational-behavior-host-application-death-payload",
    "operational-behavior-host-application-death-qos",
    "operational-behavior-host-application-death-retained",
    "operational-behavior-host-application-disconnect-intentional",
    "payloads-state-will-message",
    "payloads-state-will-message-qos",
    "payloads-state-will-message-retain",
    "payloads-state-will-message-payload",
    "payloads-state-subscribe",
    "payloads-state-birth",
    "payloads-state-birth-payload",
};

constexpr std::string_view command_why =
    "a requirement of the host that sends a command (NCMD, DCMD); the node's reading of them is "
    "tested beside (sparkplug_conformance_test.cpp: rebirth typed and not, DCMD by name and by "
    "alias without datatype)";
constexpr std::string_view command_ids[] = {
    "topics-ncmd-topic",
    "topics-ncmd-mqtt",
    "topics-ncmd-timestamp",
    "topics-ncmd-payload",
    "topics-dcmd-topic",
    "topics-dcmd-mqtt",
    "topics-dcmd-timestamp",
    "topics-dcmd-payload",
    "operational-behavior-data-commands-ncmd-rebirth-verb",
    "operational-behavior-data-commands-ncmd-rebirth-name",
    "operational-behavior-data-commands-ncmd-rebirth-value",
    "operational-behavior-data-commands-ncmd-verb",
    "operational-behavior-data-commands-ncmd-metric-name",
    "operational-behavior-data-commands-ncmd-metric-value",
    "operational-behavior-data-commands-dcmd-verb",
    "operational-behavior-data-commands-dcmd-metric-name",
    "operational-behavior-data-commands-dcmd-metric-value",
    "payloads-name-cmd-requirement",
    "payloads-ncmd-timestamp",
    "payloads-ncmd-seq",
    "payloads-ncmd-qos",
    "payloads-ncmd-retain",
    "payloads-dcmd-timestamp",
    "payloads-dcmd-seq",
    "payloads-dcmd-qos",
    "payloads-dcmd-retain",
};

constexpr std::string_view infrastructure_why =
    "about the whole infrastructure's names, which its operators assign: one node cannot show it "
    "(eip2mqtt check refuses an id that is not a topic element)";
constexpr std::string_view infrastructure_ids[] = {
    "topic-structure-namespace-unique-edge-node-descriptor",
    "topic-structure-namespace-duplicate-device-id-across-edge-node",
    "payloads-nbirth-edge-node-descriptor",
    "case-sensitivity-sparkplug-ids",
};

constexpr std::string_view may_why =
    "allows rather than requires (MAY): the node does it (a DISCONNECT after its NDEATH), nothing "
    "to judge";
constexpr std::string_view may_ids[] = {
    "operational-behavior-edge-node-intentional-disconnect-packet",
};

constexpr std::string_view datatype_why =
    "not followed, knowingly (a SHOULD NOT): DATA metrics keep their datatype, because Eclipse "
    "Tahu's decoder, and the hosts built on it, read a value by the datatype it comes with and "
    "find none without it (adapter test TahuReadsNoValueFromADataMetricWithoutItsDatatype); it "
    "costs 2 bytes a metric";
constexpr std::string_view datatype_ids[] = {
    "payloads-metric-datatype-not-req",
};

constexpr std::string_view dataset_why =
    "the node publishes no DataSet and no Template: nothing to judge (judged instead: "
    "topics-nbirth-templates, no metric of those datatypes)";
constexpr std::string_view dataset_ids[] = {
    "payloads-dataset-column-size",
    "payloads-dataset-column-num-headers",
    "payloads-dataset-types-def",
    "payloads-dataset-types-num",
    "payloads-dataset-types-type",
    "payloads-dataset-types-value",
    "payloads-dataset-parameter-type-req",
    "payloads-template-dataset-value",
    "payloads-template-definition-nbirth-only",
    "payloads-template-definition-is-definition",
    "payloads-template-definition-ref",
    "payloads-template-definition-members",
    "payloads-template-definition-nbirth",
    "payloads-template-definition-parameters",
    "payloads-template-definition-parameters-default",
    "payloads-template-instance-is-definition",
    "payloads-template-instance-ref",
    "payloads-template-instance-members",
    "payloads-template-instance-members-birth",
    "payloads-template-instance-members-data",
    "payloads-template-instance-parameters",
    "payloads-template-version",
    "payloads-template-ref-definition",
    "payloads-template-ref-instance",
    "payloads-template-is-definition",
    "payloads-template-is-definition-definition",
    "payloads-template-is-definition-instance",
    "payloads-template-parameter-name-required",
    "payloads-template-parameter-name-type",
    "payloads-template-parameter-value-type",
    "payloads-template-parameter-type-value",
    "payloads-template-parameter-type-req",
    "payloads-template-parameter-value",
};

std::vector<NotJudged> all_not_judged() {
    std::vector<NotJudged> all;
    const auto add = [&](std::span<const std::string_view> ids, std::string_view why) {
        for (const auto id : ids) all.push_back({id, why});
    };
    add(server_ids, server_why);
    add(host_ids, host_why);
    add(command_ids, command_why);
    add(infrastructure_ids, infrastructure_why);
    add(may_ids, may_why);
    add(datatype_ids, datatype_why);
    add(dataset_ids, dataset_why);
    return all;
}

}  // namespace

std::span<const NotJudged> not_judged() {
    static const std::vector<NotJudged> all = all_not_judged();
    return all;
}

}  // namespace eip2mqtt::test::conformance
