#include "synthetic_dataset.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "rollsense/dataset.hpp"

namespace rollsense::test {

namespace {

struct Lcg {
    std::uint64_t s;
    double uniform() {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(s >> 11) / 9007199254740992.0;
    }
};

// A peak with a secondary shoulder (polygons roll over edges, cylinders do not).
std::vector<double> peak(std::size_t n, double amp, double centre, double width, double shoulder, Lcg& rng) {
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i);
        const double u = (t - centre) / width, v = (t - centre - 1.2 * width) / (0.6 * width);
        x[i] = amp * (std::exp(-0.5 * u * u) + shoulder * std::exp(-0.5 * v * v)) + 0.002 * (rng.uniform() - 0.5);
    }
    return x;
}

}  // namespace

void write_synthetic_dataset(const std::filesystem::path& dir) {
    DatasetInfo info;
    info.channels = {"ch1", "ch2", "ch3"};
    info.profile = "synthetic";
    info.seed = 7;
    info.software_version = "test";
    auto w = DatasetWriter::open(dir, info, DatasetOpenMode::create);
    REQUIRE(w.ok());
    (*w)->set_commit_every(64);
    const char* objects[kSyntheticObjects] = {"C1", "C2", "C3", "S1", "S2", "P1", "P2", "H1", "H2"};
    const char* speeds[kSyntheticSpeeds] = {"10", "20"};
    Lcg rng{42};
    for (int o = 0; o < kSyntheticObjects; ++o)
        for (int s = 0; s < kSyntheticSpeeds; ++s)
            for (int r = 1; r <= kSyntheticRepetitions; ++r) {
                TrialRecord rec;
                rec.info.object = objects[o];
                rec.info.speed = speeds[s];
                rec.info.repetition = r;
                rec.info.id = rec.info.object + "-v" + rec.info.speed + "-r" + std::to_string(r);
                rec.file = "trials/" + rec.info.id + ".csv";
                const std::size_t n = s == 0 ? 180 : 120;
                const double scale = s == 0 ? 1.0 : 0.66;  // faster roll, fewer samples
                const bool polygon = o >= 3;
                const double spacing = (14.0 + 2.5 * o + 0.4 * rng.uniform()) * scale;
                const double width = (5.0 + 0.4 * (o % 3) + 0.3 * rng.uniform()) * scale;
                const double shoulder = polygon ? 0.15 + 0.05 * (o % 3) + 0.1 * rng.uniform() : 0.0;
                // The last repetition of every polygon at the fast speed: ch3 pressed throughout.
                const double stop = polygon && s == 1 && r == kSyntheticRepetitions ? 1000.0 : 0.0;
                const double c0 = 40.0 * scale;
                TrialData d;
                for (std::size_t i = 0; i < n; ++i) d.time.push_back(static_cast<double>(i) / 31.1);
                d.channels = {peak(n, 0.30 + 0.02 * o, c0, width, shoulder, rng),
                              peak(n, 0.35 + 0.01 * o, c0 + spacing, width, shoulder, rng),
                              stop > 0 ? std::vector<double>(n, 0.2)
                                       : peak(n, 0.28 + 0.015 * o, c0 + 2.0 * spacing, width, shoulder, rng)};
                d.valid.assign(n, 1);
                rec.samples = n;
                REQUIRE((*w)->add_trial(rec, d).ok());
            }
    REQUIRE((*w)->flush().ok());
    REQUIRE((*w)->write_run_info({{"date_utc", "2026-01-02T03:04:05Z"},
                                  {"command_line", "rollsense run synthetic.lua --out <dir> & friends"},
                                  {"rollsense_version", "test"},
                                  {"profile", "synthetic"},
                                  {"script", "synthetic.lua"},
                                  {"seed", "7"}})
                .ok());
}

}  // namespace rollsense::test
