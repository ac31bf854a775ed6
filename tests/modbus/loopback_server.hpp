// A libmodbus TCP server on 127.0.0.1 (ephemeral port) serving a register
// map, with a small device model stepping on its own thread: a real Modbus
// peer for the plugin's tests.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

struct _modbus_mapping_t;

namespace rollsense::testing {

class ModbusLoopbackServer {
public:
    // `step(holding, input, dt)` runs between requests with the map locked:
    // the device model moves its position toward its goal there.
    using Step = std::function<void(std::vector<std::uint16_t>& holding, std::vector<std::uint16_t>& input, double dt)>;

    ModbusLoopbackServer(int registers, Step step);
    ~ModbusLoopbackServer();

    int port() const { return port_; }
    // Keep receiving requests but never answer (a device that hung).
    void set_mute(bool mute) { mute_ = mute; }
    std::uint64_t requests() const { return requests_; }

    template <class F>
    auto with_registers(F f) {
        std::lock_guard lock(mutex_);
        return f(holding_, input_);
    }

private:
    void serve();
    void sync_in();
    void sync_out();

    void* ctx_ = nullptr;
    _modbus_mapping_t* map_ = nullptr;
    int listen_socket_ = -1;
    int port_ = 0;
    Step step_;
    std::vector<std::uint16_t> holding_, input_;
    std::mutex mutex_;
    std::atomic<bool> running_{true}, mute_{false};
    std::atomic<std::uint64_t> requests_{0};
    std::thread thread_;
};

}  // namespace rollsense::testing
