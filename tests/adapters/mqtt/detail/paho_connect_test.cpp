#include "adapters/mqtt/detail/paho_connect.hpp"

#include <MQTTAsync.h>
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "adapters/mqtt/detail/paho_trace.hpp"

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

/// A loopback TCP listener on a port of its own; the kernel completes handshakes for it
/// whether or not anything is accepted.
struct Listener {
    explicit Listener(int backlog = 8) {
        fd = ::socket(AF_INET, SOCK_STREAM, 0);
        address.sin_family = AF_INET;
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        EXPECT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
        EXPECT_EQ(::listen(fd, backlog), 0);
        socklen_t length = sizeof address;
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length);
    }
    ~Listener() { ::close(fd); }
    /// The first byte a client sends on the next connection, waiting at most 10 s.
    int first_byte_received() const {
        pollfd polled{fd, POLLIN, 0};
        if (::poll(&polled, 1, 10000) != 1) return -1;
        const int accepted = ::accept(fd, nullptr, nullptr);
        polled = {accepted, POLLIN, 0};
        unsigned char byte = 0;
        const bool read = ::poll(&polled, 1, 10000) == 1 && ::recv(accepted, &byte, 1, 0) == 1;
        ::close(accepted);
        return read ? byte : -1;
    }

    int fd = -1;
    sockaddr_in address{};
};

/// A listener whose queue of connections nobody accepts is full: the kernel drops the next
/// SYN, so a connect to it stays in progress (until the SYN's retry, a second later).
struct StalledListener : Listener {
    StalledListener() : Listener(0) {
        for (auto& held : queued) {
            held = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
            ::connect(held, reinterpret_cast<sockaddr*>(&address), sizeof address);
        }
    }
    ~StalledListener() {
        for (const int held : queued) ::close(held);
    }
    int queued[4] = {};
};

struct Outcome {
    int rc = 0;
    int error = 0;
    bool connected = false;
};

/// A non-blocking connect to `address` from a thread named `thread_name`.
Outcome connect_from(const char* thread_name, sockaddr_in address) {
    Outcome outcome;
    std::thread([&] {
        ::pthread_setname_np(::pthread_self(), thread_name);
        const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
        outcome.rc = ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address);
        outcome.error = errno;
        sockaddr_in peer{};
        socklen_t length = sizeof peer;
        outcome.connected = ::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &length) == 0;
        ::close(fd);
    }).join();
    return outcome;
}

TEST(PahoConnectTest, InPahosSendThreadAConnectHasEndedWhenItReturns) {
    const Listener listener;
    const auto outcome = connect_from("MQTTAsync_send", listener.address);
    EXPECT_EQ(outcome.rc, 0) << std::strerror(outcome.error);
    EXPECT_TRUE(outcome.connected);
}

TEST(PahoConnectTest, InPahosSendThreadARefusedConnectSaysWhy) {
    sockaddr_in closed{};
    {
        const Listener gone;  // a port that was just free, closed again
        closed = gone.address;
    }
    const auto outcome = connect_from("MQTTAsync_send", closed);
    EXPECT_EQ(outcome.rc, -1);
    EXPECT_EQ(outcome.error, ECONNREFUSED);
}

// A TLS broker's port, marked from the client's URLs: its connects take Paho's own path.
TEST(PahoConnectTest, AConnectToATlsBrokersPortIsLeftToPaho) {
    const Listener listener;
    const auto port = ntohs(listener.address.sin_port);
    EXPECT_FALSE(is_paho_tls_port(port));
    paho_connects_at_once({"tcp://127.0.0.1:1", "ssl://127.0.0.1:" + std::to_string(port)});
    EXPECT_TRUE(is_paho_tls_port(port));
    EXPECT_FALSE(is_paho_tls_port(1));
    const auto outcome = connect_from("MQTTAsync_send", listener.address);
    EXPECT_EQ(outcome.rc, -1);
    EXPECT_EQ(outcome.error, EINPROGRESS);
}

TEST(PahoConnectTest, AnyOtherThreadGetsTheCLibrarysAnswerUnchanged) {
    const Listener listener;
    const auto outcome = connect_from("eip2mqtt-loop", listener.address);
    EXPECT_EQ(outcome.rc, -1);
    EXPECT_EQ(outcome.error, EINPROGRESS);
    EXPECT_FALSE(in_paho_thread("MQTTAsync_send"));
}

TEST(PahoConnectTest, InPahosSendThreadAConnectSlowerThanTheWaitIsLeftToPaho) {
    const StalledListener listener;
    const auto outcome = connect_from("MQTTAsync_send", listener.address);
    EXPECT_EQ(outcome.rc, -1);
    EXPECT_EQ(outcome.error, EINPROGRESS);
    EXPECT_FALSE(outcome.connected);
}

TEST(PahoConnectTest, FinishConnectSaysAConnectThatGoesOnIsStillInProgress) {
    const StalledListener listener;
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
    auto address = listener.address;
    ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), -1);
    ASSERT_EQ(errno, EINPROGRESS);
    EXPECT_EQ(finish_connect(fd, std::chrono::milliseconds(0)), -1);
    EXPECT_EQ(errno, EINPROGRESS);
    ::close(fd);
}

TEST(PahoConnectTest, TheReceiveThreadsSleepEndsOnceTheSendThreadConnected) {
    const Listener listener;
    sleep_until_paho_socket(std::chrono::microseconds(0));  // what earlier tests' connects said
    auto slept = std::async(std::launch::async, [] {
        ::pthread_setname_np(::pthread_self(), "MQTTAsync_rcv");
        return ::usleep(90'000'000);  // Paho's turns are 100 ms; this one, a minute and a half
    });
    EXPECT_EQ(connect_from("MQTTAsync_send", listener.address).rc, 0);
    const bool woken = slept.wait_for(std::chrono::seconds(30)) == std::future_status::ready;
    EXPECT_TRUE(woken) << "the receive thread slept on with a socket to read";
    if (!woken) paho_socket_added();
    EXPECT_EQ(slept.get(), 0);
}

TEST(PahoConnectTest, AnyOtherThreadsSleepIsTheCLibrarys) {
    paho_socket_added();  // would end the receive thread's sleep
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(::usleep(20'000), 0);
    EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(20));
    sleep_until_paho_socket(std::chrono::microseconds(0));
}

std::mutex traced_mutex;
std::vector<std::string> traced;

void record(enum MQTTASYNC_TRACE_LEVELS /*level*/, char* message) {
    std::lock_guard lock(traced_mutex);
    traced.emplace_back(message);
}

/// Paho's own client, traced: its connect no longer waits for the receive thread's poll,
/// which Paho traces as "Connect pending" when it does.
TEST(PahoConnectTest, PahoSendsConnectWithoutLeavingTheConnectPending) {
    const Listener listener;
    const auto url = "tcp://127.0.0.1:" + std::to_string(ntohs(listener.address.sin_port));
    MQTTAsync client = nullptr;
    ASSERT_EQ(::MQTTAsync_create(&client, url.c_str(), "connect-test", MQTTCLIENT_PERSISTENCE_NONE,
                                 nullptr),
              MQTTASYNC_SUCCESS);
    ::MQTTAsync_setTraceLevel(MQTTASYNC_TRACE_MINIMUM);
    ::MQTTAsync_setTraceCallback(record);
    MQTTAsync_connectOptions options = MQTTAsync_connectOptions_initializer;
    options.connectTimeout = 30;
    ASSERT_EQ(::MQTTAsync_connect(client, &options), MQTTASYNC_SUCCESS);
    EXPECT_EQ(listener.first_byte_received(), 0x10) << "an MQTT CONNECT";
    ::MQTTAsync_setTraceCallback(nullptr);
    quiet_paho_trace(nullptr);
    ::MQTTAsync_destroy(&client);

    std::lock_guard lock(traced_mutex);
    ASSERT_FALSE(traced.empty()) << "Paho traced nothing: the test proves nothing";
    for (const auto& line : traced) EXPECT_EQ(line.find("Connect pending"), std::string::npos);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
