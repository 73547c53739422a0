#include "eip2mqtt/core/command/response_match.hpp"

#include <gtest/gtest.h>

#include "eip2mqtt/core/command/command_nak.hpp"
#include "eip2mqtt/core/command/encode.hpp"

namespace eip2mqtt::core::command {
namespace EIP2MQTT_THIS_FILE {

const wire::ExchangeKey asked_key{wire::ProducerId{0x0A000009}, 3};
const wire::ExchangeKey other_key{wire::ProducerId{0x0A000009}, 4};

struct Asked {
    Request request;
    std::vector<std::byte> bytes;
};

template <class Body>
Asked ask(const Body& body) {
    PduHeader header;
    header.request_id = 77;
    auto bytes = encode(header, body);
    return {decode_request(bytes).value(), bytes};
}

Response config_answer(const Asked& asked, wire::ExchangeKey key) {
    ExchangeConfig config;
    config.key = key;
    return decode_response(
               encode(reply_header(asked.request.header, PduType::retrieve_config_response),
                      config))
        .value();
}

TEST(ResponseMatch, ARetrieveAnswerForAnotherExchangeIsNotTheAnswer) {
    const auto asked = ask(RetrieveConfigRequest{asked_key});
    EXPECT_TRUE(answers_request(asked.request, asked.bytes, config_answer(asked, asked_key)));
    EXPECT_FALSE(answers_request(asked.request, asked.bytes, config_answer(asked, other_key)));
}

TEST(ResponseMatch, TheIdTypeAndPageMustBeTheRequests) {
    const auto asked = ask(SummaryRequest{86});
    SummaryPage page;
    page.index = 86;
    auto header = reply_header(asked.request.header, PduType::summary_response);
    EXPECT_TRUE(
        answers_request(asked.request, asked.bytes, decode_response(encode(header, page)).value()));
    page.index = 0;
    EXPECT_FALSE(
        answers_request(asked.request, asked.bytes, decode_response(encode(header, page)).value()));
    page.index = 86;
    header.request_id = 78;
    EXPECT_FALSE(
        answers_request(asked.request, asked.bytes, decode_response(encode(header, page)).value()));
    // A Retrieve answer is no answer to a Summary.
    EXPECT_FALSE(answers_request(asked.request, asked.bytes, config_answer(asked, asked_key)));
}

TEST(ResponseMatch, ANakMustEchoTheRequest) {
    const auto asked = ask(RetrieveConfigRequest{asked_key});
    auto nak = make_nak(asked.bytes, DecodeError::malformed).value();
    EXPECT_TRUE(answers_request(asked.request, asked.bytes,
                                decode_response(encode(nak.header, nak.nak)).value()));
    nak.nak.offending[12] = std::byte{0x55};
    EXPECT_FALSE(answers_request(asked.request, asked.bytes,
                                 decode_response(encode(nak.header, nak.nak)).value()));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::command
