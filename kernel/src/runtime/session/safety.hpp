// The safety side of a run, apart from any script: the emergency-stop input and the recording trigger output (through
// the SDK's DigitalLines), and the interrupt flag that Ctrl-C sets. The scheduler polls the e-stop every control
// period; a tripped e-stop stops every joint at once, locks out commands and returns the reason, which cancels the run.
#pragma once

#include <atomic>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "rollsense/digital_io.hpp"
#include "runtime/profile/profile.hpp"

namespace rollsense::runtime {

class Robot;

class Safety {
public:
    // Open the profile's safety.estop and safety.trigger lines (none: nothing to open). Fails if the e-stop is asserted
    // already.
    Status open(const Profile& profile, const DigitalLines& lines);

    // Once per control period. The reason the run must stop, once, when the e-stop is asserted or unreadable; the robot
    // is safe and locked by then.
    std::optional<std::string> check_estop(Robot& robot, double now);

    // A pulse on the trigger output (start of a recording), for `seconds`.
    void start_trigger_pulse(double now, double seconds);
    // End the pulse when its time has come.
    void update_trigger(double now);
    // When the pulse ends (infinity: no pulse); the scheduler wakes for it.
    double next_event() const { return trigger_off_ >= 0 ? trigger_off_ : kNever; }

    // Set from a signal handler (or any thread); consumed by the scheduler.
    std::atomic<bool>& interrupt_flag() { return interrupt_; }

private:
    static constexpr double kNever = std::numeric_limits<double>::infinity();
    std::unique_ptr<DigitalInput> estop_;
    std::unique_ptr<DigitalOutput> trigger_;
    double trigger_off_ = -1;  // run-clock time to end the current pulse, -1 = none
    bool estop_tripped_ = false;
    std::atomic<bool> interrupt_{false};
};

// SIGINT/SIGTERM/SIGHUP for the lifetime of this object: the first asks the run to stop through `flag` (the script is
// cancelled, its cleanup runs, the hand is made safe); the third exits at once, unless a watchdog has taken it over
// (set_hard_interrupt_handled: it makes the hand safe and writes run-info before the exit). The previous handlers come
// back after.
int interrupts_received();
void set_hard_interrupt_handled(bool handled);

class InterruptGuard {
public:
    explicit InterruptGuard(std::atomic<bool>& flag);
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

private:
    struct Saved;
    std::unique_ptr<Saved> saved_;
};

}  // namespace rollsense::runtime
