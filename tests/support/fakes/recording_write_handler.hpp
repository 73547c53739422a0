#pragma once
// A fake WriteHandler (where a northbound or the command responder hands the writes it decoded):
// it keeps each request, in order, and refuses it on demand.

#include <utility>
#include <vector>

#include "eip2mqtt/app/northbound/northbound.hpp"

namespace eip2mqtt::test {

/// Keeps what it is handed, and refuses it on demand.
class RecordingWriteHandler : public app::WriteHandler {
public:
    void on_write(app::WriteRequest&& request) override {
        if (refuse) {
            request.reply.origin->write_result(request.reply, "rate limited");
            return;
        }
        requests.push_back(std::move(request));
    }
    std::vector<app::WriteRequest> requests;
    bool refuse = false;
};

}  // namespace eip2mqtt::test
