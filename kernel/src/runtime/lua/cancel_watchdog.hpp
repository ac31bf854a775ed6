// The last line behind the sandbox's cancel: a thread that watches the run (slice limit, Ctrl-C, e-stop, time
// budget). Lua hands control back to the scheduler within one hook period of a cancel, unless something no hook
// reaches holds it: C++ work that takes long, a C library call. If Lua has not handed control back `grace_ms` after a
// cancel was seen or after the slice limit passed, or at once on the third Ctrl-C, the watchdog calls `last_resort`
// on its own thread: the hand made safe under the robot's device lock (or by the prepared last resort if the script's
// thread holds it), run-info written, the process ended (Session::last_resort).
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "rollsense/status.hpp"

namespace rollsense::runtime {

class Sandbox;

class CancelWatchdog {
public:
    using LastResort = std::function<void(const std::string& why, ErrorCode code)>;  // code: of the run-info
    CancelWatchdog(const Sandbox& sandbox, const std::atomic<bool>& interrupt, double grace_ms, LastResort last_resort);
    ~CancelWatchdog();
    CancelWatchdog(const CancelWatchdog&) = delete;
    CancelWatchdog& operator=(const CancelWatchdog&) = delete;

private:
    void watch();

    const Sandbox& sandbox_;
    const std::atomic<bool>& interrupt_;
    double grace_ms_;
    LastResort last_resort_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::thread thread_;  // last: starts once everything above is set
};

}  // namespace rollsense::runtime
