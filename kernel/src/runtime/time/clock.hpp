// Injected time. The scheduler never reads a clock directly: with the virtual clock (simulation) time jumps to the
// next event, so a run goes as fast as the CPU allows and is deterministic; with the monotonic clock (hardware) the
// scheduler sleeps until the event. The same script runs on both.
#pragma once

#include <memory>

namespace rollsense::runtime {

class Clock {
public:
    virtual ~Clock() = default;
    virtual double now() const = 0;           // seconds since the run started
    virtual void sleep_until(double t) = 0;   // returns at once if t <= now()
    virtual bool is_virtual() const = 0;
    // Round a duration to the virtual clock's grid (2^-20 s), so that time differences are exact and a trial does not
    // depend on when it started. Real clocks have no grid: unchanged.
    double quantize(double t) const;
};

class VirtualClock final : public Clock {
public:
    double now() const override { return now_; }
    void sleep_until(double t) override {
        if (t > now_) now_ = t;
    }
    bool is_virtual() const override { return true; }

private:
    double now_ = 0.0;
};

class MonotonicClock final : public Clock {
public:
    MonotonicClock();
    double now() const override;
    void sleep_until(double t) override;
    bool is_virtual() const override { return false; }

private:
    double origin_;
};

std::unique_ptr<Clock> make_clock(bool virtual_time);

}  // namespace rollsense::runtime
