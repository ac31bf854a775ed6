#include "rollsense/hal/modbus_client.hpp"

#include <modbus/modbus.h>

#include <cerrno>
#include <utility>

namespace rollsense::hal {
namespace {
modbus_t* as_ctx(void* p) { return static_cast<modbus_t*>(p); }
}  // namespace

std::string ModbusLink::describe() const {
    if (transport == Transport::tcp)
        return "modbus tcp " + host + ":" + std::to_string(port) + " slave " + std::to_string(slave);
    return "modbus rtu " + device + " " + std::to_string(baud) + " " + std::to_string(data_bits) + parity +
           std::to_string(stop_bits) + " slave " + std::to_string(slave);
}

Result<ModbusClient> ModbusClient::connect(const ModbusLink& link) {
    modbus_t* ctx = nullptr;
    if (link.transport == ModbusLink::Transport::tcp) {
        ctx = modbus_new_tcp(link.host.c_str(), link.port);
    } else {
        if (link.parity != 'N' && link.parity != 'E' && link.parity != 'O')
            return Error{ErrorCode::invalid_argument,
                         link.describe() + ": parity must be N, E or O (got '" + std::string(1, link.parity) + "')"};
        ctx = modbus_new_rtu(link.device.c_str(), link.baud, link.parity, link.data_bits, link.stop_bits);
    }
    if (!ctx)
        return Error{ErrorCode::invalid_argument,
                     link.describe() + ": libmodbus refused the settings: " + modbus_strerror(errno)};
    ModbusClient client(ctx, link);
    if (modbus_set_slave(ctx, link.slave) != 0)
        return Error{ErrorCode::invalid_argument,
                     link.describe() + ": invalid slave id (1-247): " + modbus_strerror(errno)};
    const auto ms = link.timeout.count();
    modbus_set_response_timeout(ctx, static_cast<std::uint32_t>(ms / 1000),
                                static_cast<std::uint32_t>((ms % 1000) * 1000));
    if (modbus_connect(ctx) != 0) {
        const int err = errno;
        std::string hint = link.transport == ModbusLink::Transport::tcp
                               ? "; is the device on the network and listening on that port?"
                               : "; is the adapter plugged in and are you in the 'dialout' group?";
        return Error{err == ENOENT ? ErrorCode::not_found : ErrorCode::io_error,
                     link.describe() + ": cannot connect: " + modbus_strerror(err) + hint};
    }
    return client;
}

ModbusClient::~ModbusClient() { close(); }

ModbusClient::ModbusClient(ModbusClient&& other) noexcept
    : ctx_(std::exchange(other.ctx_, nullptr)), link_(std::move(other.link_)) {}

ModbusClient& ModbusClient::operator=(ModbusClient&& other) noexcept {
    if (this != &other) {
        close();
        ctx_ = std::exchange(other.ctx_, nullptr);
        link_ = std::move(other.link_);
    }
    return *this;
}

void ModbusClient::close() noexcept {
    if (ctx_) {
        modbus_close(as_ctx(ctx_));
        modbus_free(as_ctx(ctx_));
    }
    ctx_ = nullptr;
}

Error ModbusClient::error_for(int err, const std::string& what) const {
    const std::string head = link_.describe() + ": " + what + ": ";
    switch (err) {
        case ETIMEDOUT:
            return {ErrorCode::timeout, head + "no answer within " + std::to_string(link_.timeout.count()) + " ms (" +
                                            std::to_string(link_.retries + 1) +
                                            " attempts); check power, slave id, wiring and the line settings"};
        case EMBXILFUN:
            return {ErrorCode::unsupported, head + "the device does not support this function (exception 1)"};
        case EMBXILADD:
            return {ErrorCode::invalid_argument,
                    head + "the device has no such register (exception 2); check the register map in the profile"};
        case EMBXILVAL:
            return {ErrorCode::limit_violation, head + "the device refused the value (exception 3)"};
        case EMBXSFAIL:
            return {ErrorCode::hardware_fault, head + "the device reported a failure (exception 4)"};
        case EMBXSBUSY:
            return {ErrorCode::hardware_fault, head + "the device is busy (exception 6)"};
        case EMBBADCRC:
        case EMBBADDATA:
        case EMBBADEXC:
        case EMBUNKEXC:
        case EMBMDATA:
        case EMBBADSLAVE:
            return {ErrorCode::protocol_error, head + modbus_strerror(err)};
        default:
            return {ErrorCode::io_error, head + modbus_strerror(err)};
    }
}

template <class Op>
Status ModbusClient::attempt(const std::string& what, Op op) {
    if (!ctx_) return {ErrorCode::state_error, link_.describe() + ": not connected"};
    int err = 0;
    for (int i = 0; i <= link_.retries; ++i) {
        if (op() >= 0) return {};
        err = errno;
        const bool transient = err == ETIMEDOUT || err == EMBBADCRC || err == EMBBADDATA;
        if (!transient) break;
        modbus_flush(as_ctx(ctx_));
    }
    return error_for(err, what);
}

Result<std::vector<std::uint16_t>> ModbusClient::read_holding(int address, int count) {
    std::vector<std::uint16_t> out(static_cast<std::size_t>(count));
    const std::string what = "read of " + std::to_string(count) + " holding register(s) at " + std::to_string(address);
    auto st = attempt(what, [&] { return modbus_read_registers(as_ctx(ctx_), address, count, out.data()); });
    if (!st.ok()) return st;
    return out;
}

Result<std::vector<std::uint16_t>> ModbusClient::read_input(int address, int count) {
    std::vector<std::uint16_t> out(static_cast<std::size_t>(count));
    const std::string what = "read of " + std::to_string(count) + " input register(s) at " + std::to_string(address);
    auto st = attempt(what, [&] { return modbus_read_input_registers(as_ctx(ctx_), address, count, out.data()); });
    if (!st.ok()) return st;
    return out;
}

Status ModbusClient::write_registers(int address, std::span<const std::uint16_t> values) {
    const std::string what =
        "write of " + std::to_string(values.size()) + " register(s) at " + std::to_string(address);
    return attempt(what, [&] {
        return modbus_write_registers(as_ctx(ctx_), address, static_cast<int>(values.size()), values.data());
    });
}

Status ModbusClient::write_register(int address, std::uint16_t value) {
    return attempt("write of register " + std::to_string(address),
                   [&] { return modbus_write_register(as_ctx(ctx_), address, value); });
}

}  // namespace rollsense::hal
