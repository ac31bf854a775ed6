#include "runtime/lua/cancel_watchdog.hpp"

#include <algorithm>
#include <chrono>

#include "runtime/lua/sandbox.hpp"
#include "runtime/session/safety.hpp"

namespace rollsense::runtime {
namespace {

constexpr auto kPoll = std::chrono::milliseconds(20);

std::int64_t now_ms() {
    using namespace std::chrono;
    return static_cast<std::int64_t>(duration<double, std::milli>(steady_clock::now().time_since_epoch()).count());
}

}  // namespace

CancelWatchdog::CancelWatchdog(const Sandbox& sandbox, const std::atomic<bool>& interrupt, double grace_ms,
                               LastResort last_resort)
    : sandbox_(sandbox), interrupt_(interrupt), grace_ms_(grace_ms), last_resort_(std::move(last_resort)) {
    set_hard_interrupt_handled(true);  // the third Ctrl-C is ours: safe state before the exit
    thread_ = std::thread([this] { watch(); });
}

CancelWatchdog::~CancelWatchdog() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
    set_hard_interrupt_handled(false);
}

void CancelWatchdog::watch() {
    std::int64_t cancel_seen = 0;  // when this thread first saw the current cancel
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, kPoll, [this] { return stop_; })) {
        if (interrupts_received() >= 3) {
            last_resort_("interrupted three times: the watchdog made the hand safe and ended the run",
                         ErrorCode::cancelled);
            return;
        }
        const std::int64_t t = now_ms(), in_lua = sandbox_.in_lua_since_ms();
        // One call no hook interrupts (table.move over 2^62 slots), past the slice limit: nothing else ends it.
        if (in_lua != 0 && static_cast<double>(t - in_lua) > sandbox_.limits().max_slice_ms + grace_ms_) {
            last_resort_("the script spent " + std::to_string(t - in_lua) + " ms in one call no hook reaches (a C function "
                         "on a huge input?), past --slice-limit-ms: the watchdog made the hand safe and ended the run",
                         ErrorCode::limit_violation);
            return;
        }
        if (!sandbox_.cancelled() && !interrupt_.load()) {
            cancel_seen = 0;  // cleared (cleanup runs on a fresh cancel)
            continue;
        }
        if (cancel_seen == 0) cancel_seen = t;
        if (in_lua == 0) continue;  // the scheduler has control: the cancel is being acted on
        if (static_cast<double>(t - std::max(cancel_seen, in_lua)) > grace_ms_) {
            last_resort_("the script did not stop within " + std::to_string(static_cast<long>(grace_ms_)) +
                         " ms of being cancelled (stuck where no hook runs): the watchdog made the hand safe and "
                         "ended the run", ErrorCode::cancelled);
            return;
        }
    }
}

}  // namespace rollsense::runtime
