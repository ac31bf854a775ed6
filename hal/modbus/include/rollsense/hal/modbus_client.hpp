// A Modbus client over libmodbus, RTU (serial) or TCP.
//
// Every call returns a typed error naming the link ("tcp 127.0.0.1:1502 slave
// 9"), the function and the registers; a timeout is retried `retries` times
// after flushing the link (a late reply must not answer the next request).
#pragma once

#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::hal {

struct ModbusLink {
    enum class Transport { tcp, rtu } transport = Transport::tcp;
    std::string host = "127.0.0.1";  // tcp
    int port = 502;                  // tcp
    std::string device;              // rtu, e.g. /dev/ttyUSB0
    int baud = 115200;               // rtu
    char parity = 'N';               // rtu: 'N', 'E' or 'O'
    int data_bits = 8;               // rtu
    int stop_bits = 1;               // rtu
    int slave = 1;
    std::chrono::milliseconds timeout{100};
    int retries = 2;

    std::string describe() const;  // "tcp 127.0.0.1:502 slave 1"
};

class ModbusClient {
public:
    ModbusClient() = default;
    ~ModbusClient();
    ModbusClient(const ModbusClient&) = delete;
    ModbusClient& operator=(const ModbusClient&) = delete;
    ModbusClient(ModbusClient&& other) noexcept;
    ModbusClient& operator=(ModbusClient&& other) noexcept;

    static Result<ModbusClient> connect(const ModbusLink& link);

    const ModbusLink& link() const { return link_; }
    bool is_open() const { return ctx_ != nullptr; }

    Result<std::vector<std::uint16_t>> read_holding(int address, int count);  // FC03
    Result<std::vector<std::uint16_t>> read_input(int address, int count);    // FC04
    Status write_registers(int address, std::span<const std::uint16_t> values);  // FC16
    Status write_register(int address, std::uint16_t value);                     // FC06

    void close() noexcept;

private:
    explicit ModbusClient(void* ctx, ModbusLink link) : ctx_(ctx), link_(std::move(link)) {}
    // Run `op` with bounded retries on timeouts; `what` names the request.
    template <class Op>
    Status attempt(const std::string& what, Op op);
    Error error_for(int err, const std::string& what) const;

    void* ctx_ = nullptr;  // modbus_t*, opaque so users need not include libmodbus
    ModbusLink link_;
};

}  // namespace rollsense::hal
