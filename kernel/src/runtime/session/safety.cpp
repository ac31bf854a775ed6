#include "runtime/session/safety.hpp"

#include <csignal>
#include <unistd.h>

#include "rollsense/log.hpp"
#include "runtime/robot/robot.hpp"

namespace rollsense::runtime {

Status Safety::open(const Profile& profile, const DigitalLines& lines) {
    if (profile.estop) {
        DigitalLine c{profile.estop->chip, profile.estop->line, profile.estop->active_low, "rollsense-estop"};
        if (!lines.open_input)
            return {ErrorCode::invalid_argument, profile.at("safety.estop") + ": this program cannot open digital lines; "
                                                        "run it with `rollsense run`, or remove safety.estop"};
        auto in = lines.open_input(c);
        if (!in) return Status(in.error()).with_context(profile.at("safety.estop"));
        estop_ = std::move(*in);
        auto active = estop_->is_active();
        if (!active) return Status(active.error()).with_context(profile.at("safety.estop"));
        if (*active)
            return {ErrorCode::cancelled, "the emergency stop (" + c.chip + " line " + std::to_string(c.line) +
                                              ") is asserted; release it before starting a run"};
    }
    if (profile.trigger) {
        DigitalLine c{profile.trigger->chip, profile.trigger->line, profile.trigger->active_low, "rollsense-trigger"};
        if (!lines.open_output)
            return {ErrorCode::invalid_argument, profile.at("safety.trigger") + ": this program cannot open digital lines; "
                                                          "run it with `rollsense run`, or remove safety.trigger"};
        auto out = lines.open_output(c, false);
        if (!out) return Status(out.error()).with_context(profile.at("safety.trigger"));
        trigger_ = std::move(*out);
    }
    return {};
}

std::optional<std::string> Safety::check_estop(Robot& robot, double now) {
    if (!estop_ || estop_tripped_) return std::nullopt;
    auto active = estop_->is_active();
    if (active && !*active) return std::nullopt;
    estop_tripped_ = true;
    std::string reason = active ? "emergency stop asserted"
                                : "emergency stop input unreadable (" + active.error().message + ")";
    robot.safe_state(now);  // first, within this control period
    robot.set_commands_locked(true, reason + "; commands are refused until the run ends");
    return reason;
}

void Safety::start_trigger_pulse(double now, double seconds) {
    if (!trigger_) return;
    if (auto s = trigger_->set_active(true); !s.ok()) log_warning("kernel", "trigger output: " + s.message());
    trigger_off_ = now + seconds;
}

void Safety::update_trigger(double now) {
    if (!trigger_ || trigger_off_ < 0 || now < trigger_off_) return;
    trigger_off_ = -1;
    if (auto s = trigger_->set_active(false); !s.ok()) log_warning("kernel", "trigger output: " + s.message());
}

// ------------------------------------------------------------ interrupts --

namespace {
std::atomic<std::atomic<bool>*> g_flag{nullptr};
std::atomic<int> g_count{0};
std::atomic<bool> g_hard_handled{false};

extern "C" void on_interrupt(int) {
    if (auto* f = g_flag.load()) f->store(true);
    if (g_count.fetch_add(1) >= 2 && !g_hard_handled.load()) {
        const char msg[] = "\nrollsense: interrupted three times, exiting without cleanup\n";
        (void)!::write(STDERR_FILENO, msg, sizeof msg - 1);
        ::_exit(130);
    }
}
}  // namespace

int interrupts_received() { return g_count.load(); }
void set_hard_interrupt_handled(bool handled) { g_hard_handled.store(handled); }

struct InterruptGuard::Saved {
    struct sigaction old_int {}, old_term {}, old_hup {};
};

InterruptGuard::InterruptGuard(std::atomic<bool>& flag) : saved_(std::make_unique<Saved>()) {
    g_flag.store(&flag);
    g_count.store(0);
    struct sigaction sa {};
    sa.sa_handler = &on_interrupt;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &saved_->old_int);
    sigaction(SIGTERM, &sa, &saved_->old_term);
    // A closed terminal (ssh dropped) ends the run the same way, hand made safe.
    sigaction(SIGHUP, &sa, &saved_->old_hup);
}

InterruptGuard::~InterruptGuard() {
    sigaction(SIGINT, &saved_->old_int, nullptr);
    sigaction(SIGTERM, &saved_->old_term, nullptr);
    sigaction(SIGHUP, &saved_->old_hup, nullptr);
    g_flag.store(nullptr);
}

}  // namespace rollsense::runtime
