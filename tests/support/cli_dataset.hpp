// A small dataset recorded through DatasetWriter for the end-to-end tests of
// the learning commands: three objects whose peaks differ in amplitude and
// spacing, 12 rolls each; one roll per object stops on the sensor (incomplete
// ch3) and must be rejected.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "rollsense/dataset.hpp"

namespace rollsense::testing {

inline std::vector<double> bump(std::size_t n, double amp, double centre, double width) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double u = (static_cast<double>(i) - centre) / width;
        x[i] = amp * std::exp(-0.5 * u * u);
    }
    return x;
}

// DIR/dataset (DIR unique to the process, emptied first), recorded with `seed` (0: none); returns DIR.
inline std::filesystem::path make_dataset(std::uint64_t seed = 0) {
    const auto dir = std::filesystem::temp_directory_path() / ("rollsense-test-cli-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    DatasetInfo info;
    info.channels = {"ch1", "ch2", "ch3"};
    info.seed = seed;
    auto w = DatasetWriter::open(dir / "dataset", info, DatasetOpenMode::create);
    REQUIRE(w.ok());
    const char* objects[] = {"C1", "P1", "S2"};
    for (int o = 0; o < 3; ++o)
        for (int r = 0; r < 12; ++r) {
            TrialRecord rec;
            rec.info.id = std::string(objects[o]) + "-r" + std::to_string(r);
            rec.info.object = objects[o];
            rec.info.speed = "10";
            rec.info.repetition = r;
            TrialData d;
            const std::size_t n = 140;
            for (std::size_t i = 0; i < n; ++i) d.time.push_back(static_cast<double>(i) / 31.1);
            const double spacing = 12.0 + 6.0 * o + 0.3 * r;
            const double stop = r == 11 ? 60.0 : 0.0;
            d.channels = {bump(n, 0.2 + 0.1 * o, 35, 6), bump(n, 0.25 + 0.1 * o, 35 + spacing, 6),
                          bump(n, 0.2 + 0.05 * o, 35 + 2 * spacing + stop, 6)};
            d.valid.assign(n, 1);
            rec.samples = n;
            REQUIRE((*w)->add_trial(rec, d).ok());
        }
    REQUIRE((*w)->flush().ok());
    return dir;
}


}  // namespace rollsense::testing
