// Cancellation of a run: the one flag every part of a run consults (the scheduler between steps, a script engine
// inside its own code). It is an interface because a script engine may have to own the flag itself: the Lua sandbox
// checks it from an instruction hook and sets it on its own (an endless loop, the Ctrl-C flag), so it implements
// this; C++-only runs use CancelToken.
#pragma once

#include <string>

namespace rollsense::runtime {

class Cancellation {
public:
    virtual ~Cancellation() = default;
    // The first reason wins; later calls keep it.
    virtual void cancel(const std::string& reason) = 0;
    virtual void clear_cancel() = 0;
    virtual bool cancelled() const = 0;
    virtual const std::string& cancel_reason() const = 0;
};

class CancelToken final : public Cancellation {
public:
    void cancel(const std::string& reason) override {
        if (!cancelled_) reason_ = reason;
        cancelled_ = true;
    }
    void clear_cancel() override {
        cancelled_ = false;
        reason_.clear();
    }
    bool cancelled() const override { return cancelled_; }
    const std::string& cancel_reason() const override { return reason_; }

private:
    bool cancelled_ = false;
    std::string reason_;
};

}  // namespace rollsense::runtime
