// The seed of a replay run. A replay reproduces its recording only with the
// recording's --seed: the procedure jitters its recording margins with
// rs.random(), seeded from the run seed and the trial id. So when --seed is
// not given and the profile replays a dataset (a device with a `dataset`
// parameter, as share/profiles/replay.lua has), the run takes the seed the
// dataset was recorded with (its dataset-info.csv).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "runtime/session/session.hpp"

namespace rollsense::cli {

struct RecordedSeed {
    std::uint64_t seed = 0;
    std::filesystem::path dataset;
};

// The recorded seed of the first device that replays a dataset with a seed,
// or nothing (no such device, or the profile or dataset does not open: the
// run itself then reports that, where it always has).
std::optional<RecordedSeed> recorded_seed(const runtime::SessionOptions& options);

}  // namespace rollsense::cli
