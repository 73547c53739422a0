#pragma once
/// The libmosquitto session the bench's MQTT programs share: connect to `--host`/`--port` with
/// the three callbacks and start libmosquitto's network thread. Bench-only.

#include <mosquitto.h>

#include <string>

#include "bench_common.hpp"

namespace bench {

struct MosquittoCallbacks {
    void (*on_connect)(mosquitto*, void*, int);
    void (*on_subscribe)(mosquitto*, void*, int, int, const int*);
    void (*on_message)(mosquitto*, void*, const mosquitto_message*);
};

/// Connected and looping, or the program fails with a message. `nodelay`: TCP_NODELAY, for a
/// client whose own publications are timed. `--username` (and `--password`), where the program
/// takes them, log in.
inline mosquitto* start_mosquitto(const Options& opt, const std::string& default_id, void* user,
                                  const MosquittoCallbacks& callbacks, bool nodelay) {
    mosquitto_lib_init();
    mosquitto* mosq = mosquitto_new(opt.str("id", default_id).c_str(), true, user);
    if (nodelay) mosquitto_int_option(mosq, MOSQ_OPT_TCP_NODELAY, 1);
    mosquitto_connect_callback_set(mosq, callbacks.on_connect);
    mosquitto_subscribe_callback_set(mosq, callbacks.on_subscribe);
    mosquitto_message_callback_set(mosq, callbacks.on_message);
    // A broker that wants a login (ejabberd's anonymous one: any name, a non-empty password).
    if (opt.has("username")) {
        const std::string password = opt.str("password", "");
        mosquitto_username_pw_set(mosq, opt.str("username", "").c_str(),
                                  opt.has("password") ? password.c_str() : nullptr);
    }
    if (mosquitto_connect(mosq, opt.str("host", "127.0.0.1").c_str(),
                          static_cast<int>(opt.num("port", 1883)), 60) != MOSQ_ERR_SUCCESS) {
        Options::fail("cannot connect to the broker");
    }
    mosquitto_loop_start(mosq);
    return mosq;
}

}  // namespace bench
