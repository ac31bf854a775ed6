#include "loopback_server.hpp"

#include <arpa/inet.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>

namespace rollsense::testing {

namespace {
modbus_t* as_ctx(void* p) { return static_cast<modbus_t*>(p); }
}  // namespace

ModbusLoopbackServer::ModbusLoopbackServer(int registers, Step step)
    : step_(std::move(step)),
      holding_(static_cast<std::size_t>(registers), 0),
      input_(static_cast<std::size_t>(registers), 0) {
    ctx_ = modbus_new_tcp("127.0.0.1", 0);  // port 0: the kernel picks a free one
    map_ = modbus_mapping_new(0, 0, registers, registers);
    if (!ctx_ || !map_) throw std::runtime_error("libmodbus: cannot create the server");
    listen_socket_ = modbus_tcp_listen(as_ctx(ctx_), 1);
    if (listen_socket_ < 0) throw std::runtime_error(std::string("modbus_tcp_listen: ") + modbus_strerror(errno));
    sockaddr_in addr{};
    socklen_t len = sizeof addr;
    getsockname(listen_socket_, reinterpret_cast<sockaddr*>(&addr), &len);
    port_ = ntohs(addr.sin_port);
    thread_ = std::thread([this] { serve(); });
}

ModbusLoopbackServer::~ModbusLoopbackServer() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
    if (listen_socket_ >= 0) ::close(listen_socket_);
    modbus_mapping_free(map_);
    modbus_close(as_ctx(ctx_));
    modbus_free(as_ctx(ctx_));
}

void ModbusLoopbackServer::sync_in() {
    for (std::size_t i = 0; i < holding_.size(); ++i) {
        map_->tab_registers[i] = holding_[i];
        map_->tab_input_registers[i] = input_[i];
    }
}

void ModbusLoopbackServer::sync_out() {
    for (std::size_t i = 0; i < holding_.size(); ++i) holding_[i] = map_->tab_registers[i];
}

void ModbusLoopbackServer::serve() {
    using Clock = std::chrono::steady_clock;
    auto last = Clock::now();
    int client = -1;
    std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
    while (running_) {
        pollfd p{client >= 0 ? client : listen_socket_, POLLIN, 0};
        const int r = ::poll(&p, 1, 5);
        {
            std::lock_guard lock(mutex_);
            const auto now = Clock::now();
            step_(holding_, input_, std::chrono::duration<double>(now - last).count());
            last = now;
        }
        if (r <= 0) continue;
        if (client < 0) {
            int s = listen_socket_;
            client = modbus_tcp_accept(as_ctx(ctx_), &s);
            continue;
        }
        const int n = modbus_receive(as_ctx(ctx_), query);
        if (n < 0) {  // the client went away: wait for the next one
            ::close(client);
            modbus_set_socket(as_ctx(ctx_), -1);
            client = -1;
            continue;
        }
        if (n == 0) continue;
        ++requests_;
        if (mute_) continue;
        std::lock_guard lock(mutex_);
        sync_in();
        modbus_reply(as_ctx(ctx_), query, n, map_);
        sync_out();
    }
    if (client >= 0) {
        ::close(client);
        modbus_set_socket(as_ctx(ctx_), -1);
    }
}

}  // namespace rollsense::testing
