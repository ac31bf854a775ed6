// The Linux backend: /dev/i2c-N through the i2c-dev ioctls.
//
//  - I2C_FUNCS once at open: what the adapter can do. A transfer it cannot do
//    is refused here with a message, instead of a confusing EOPNOTSUPP later.
//  - I2C_RDWR for combined transfers (repeated START between messages, one STOP).
//  - I2C_SLAVE + I2C_SMBUS(QUICK) for address-only transfers: I2C_RDWR with a
//    zero-length message is refused by many adapters, SMBus quick is the
//    portable way and what the TakkStrip's select/deselect needs.
#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "rollsense/hal/i2c.hpp"

namespace rollsense::hal {
namespace {

class LinuxI2cBus final : public I2cBus {
public:
    LinuxI2cBus(std::string path, int fd, unsigned long funcs) : path_(std::move(path)), fd_(fd) {
        funcs_.raw = funcs;
        funcs_.combined_transfers = (funcs & I2C_FUNC_I2C) != 0;
        funcs_.smbus_quick = (funcs & I2C_FUNC_SMBUS_QUICK) != 0;
    }
    ~LinuxI2cBus() override { ::close(fd_); }
    LinuxI2cBus(const LinuxI2cBus&) = delete;
    LinuxI2cBus& operator=(const LinuxI2cBus&) = delete;

    const std::string& name() const override { return path_; }
    I2cFunctionality functionality() const override { return funcs_; }

    Status transfer(std::span<I2cMessage> messages) override {
        if (messages.empty()) return {};
        if (messages.size() > kI2cMaxMessages)
            return Status(ErrorCode::invalid_argument, "i2c " + path_ + ": " + std::to_string(messages.size()) +
                                                           " messages in one transfer, the kernel allows at most 42");
        if (!funcs_.combined_transfers)
            return Status(ErrorCode::unsupported,
                          "i2c " + path_ + ": the adapter does not support plain I2C transfers (I2C_FUNC_I2C); "
                                           "it is an SMBus-only controller — use another I2C bus");
        std::vector<i2c_msg> msgs(messages.size());
        for (std::size_t i = 0; i < messages.size(); ++i) {
            if (messages[i].address > 0x7f || messages[i].data.size() > 8192)
                return Status(ErrorCode::invalid_argument, "i2c " + path_ + ": message " + std::to_string(i) +
                                                               " has a 10-bit address or more than 8192 bytes");
            msgs[i].addr = messages[i].address;
            msgs[i].flags = messages[i].read ? I2C_M_RD : 0;
            msgs[i].len = static_cast<__u16>(messages[i].data.size());
            msgs[i].buf = messages[i].data.data();
        }
        i2c_rdwr_ioctl_data request{msgs.data(), static_cast<__u32>(msgs.size())};
        std::lock_guard lock(mutex_);
        if (::ioctl(fd_, I2C_RDWR, &request) < 0) {
            const int err = errno;
            return i2c_transfer_error(path_, messages.front().address,
                                      messages.size() > 1 ? "combined transfer" : (messages.front().read ? "read" : "write"),
                                      err);
        }
        return {};
    }

    Status quick(std::uint8_t address, bool read) override {
        if (!funcs_.smbus_quick)
            return Status(ErrorCode::unsupported,
                          "i2c " + path_ + ": the adapter does not support SMBus quick commands "
                                           "(I2C_FUNC_SMBUS_QUICK), which TakkStrip select/deselect needs; use an "
                                           "adapter that does (most SoC I2C controllers and i2c-gpio do)");
        std::lock_guard lock(mutex_);
        if (slave_ != address) {
            if (::ioctl(fd_, I2C_SLAVE, static_cast<unsigned long>(address)) < 0)
                return i2c_transfer_error(path_, address, "setting the slave address", errno);
            slave_ = address;
        }
        i2c_smbus_ioctl_data request{};
        request.read_write = read ? I2C_SMBUS_READ : I2C_SMBUS_WRITE;
        request.command = 0;
        request.size = I2C_SMBUS_QUICK;
        request.data = nullptr;
        if (::ioctl(fd_, I2C_SMBUS, &request) < 0)
            return i2c_transfer_error(path_, address, read ? "quick read" : "quick write", errno);
        return {};
    }

    void sleep_for(std::chrono::microseconds duration) override { std::this_thread::sleep_for(duration); }

private:
    std::string path_;
    int fd_;
    I2cFunctionality funcs_;
    std::mutex mutex_;  // the slave address set by I2C_SLAVE is per file descriptor state
    int slave_ = -1;
};

}  // namespace

Result<std::shared_ptr<I2cBus>> open_linux_i2c_bus(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CLOEXEC);
    if (fd < 0) {
        const int err = errno;
        if (err == ENOENT || err == ENODEV || err == ENXIO)
            return Error{ErrorCode::not_found,
                         "I2C bus " + path + " not found (no such device node): load i2c-dev (sudo modprobe i2c-dev), "
                         "enable the controller (e.g. dtparam=i2c_arm=on on a Raspberry Pi) and list buses with "
                         "'i2cdetect -l'"};  // the way without hardware is the caller's: a profile's, a command's
        if (err == EACCES || err == EPERM)
            return Error{ErrorCode::io_error, "permission denied opening I2C bus " + path +
                                                  ": add your user to the 'i2c' group (sudo usermod -aG i2c $USER, "
                                                  "then log in again) or install a udev rule for i2c-dev"};
        return Error{ErrorCode::io_error, "cannot open I2C bus " + path + ": " + std::strerror(err)};
    }
    unsigned long funcs = 0;
    if (::ioctl(fd, I2C_FUNCS, &funcs) < 0) {
        const int err = errno;
        ::close(fd);
        return Error{ErrorCode::io_error, path + " is not an i2c-dev device node (I2C_FUNCS failed: " +
                                              std::strerror(err) + ")"};
    }
    return std::shared_ptr<I2cBus>(std::make_shared<LinuxI2cBus>(path, fd, funcs));
}

}  // namespace rollsense::hal
