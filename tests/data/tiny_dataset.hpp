// The smallest dataset the data-layer tests write: one channel, two samples
// per trial, trials named by id.
#pragma once

#include <string>

#include "rollsense/dataset.hpp"

namespace rollsense::testing {

inline DatasetInfo tiny_info() {
    DatasetInfo i;
    i.channels = {"ch1"};
    i.profile = "test";
    i.seed = 3;
    return i;
}

inline TrialData tiny_samples() {
    TrialData d;
    d.time = {0.0, 0.1};
    d.channels = {{1.0, 2.0}};
    d.valid = {1, 1};
    return d;
}

inline TrialRecord tiny_record(const std::string& id) {
    TrialRecord r;
    r.info.id = id;
    r.info.object = "C1";
    return r;
}

}  // namespace rollsense::testing
