// Sensor plugin interface.
//
// The kernel's sampling loop (C++, fixed rate, 31.1 Hz by default) calls read() once per sample while a script records.
// A sensor describes its channels once; every frame has one value per channel.
#pragma once

#include <vector>

#include "rollsense/component.hpp"
#include "rollsense/types.hpp"

namespace rollsense {

class ROLLSENSE_API Sensor : public Component {
public:
    // Fixed after on_configure.
    virtual std::vector<ChannelInfo> channels() const = 0;

    // The script announced the next trial (object, speed, repetition, seed).
    virtual Status begin_trial(const TrialInfo& trial) {
        (void)trial;
        return {};
    }
    // Recording starts now; a sensor that subtracts a baseline takes it here.
    virtual Status start_recording(const SampleInput& input) {
        (void)input;
        return {};
    }
    // Fill `out` (values already sized to channels().size(), time set). A read failure is reported in the frame
    // (valid=false, reason), not as a Status; a Status error means the sensor itself is broken and moves it to `error`.
    virtual Status read(const SampleInput& input, Frame& out) = 0;
    virtual Status stop_recording() { return {}; }
    virtual Status end_trial() { return {}; }
};

}  // namespace rollsense
