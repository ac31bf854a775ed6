// The feature options (`rollsense features`, and through the same parsing
// evaluate, train, report and predict) refused outside the range the
// extraction needs, naming the option and the range: exit 2, nothing written.
#include <catch2/catch.hpp>

#include "cli_helpers.hpp"

namespace {
using namespace rollsense::testing;
namespace fs = std::filesystem;
}  // namespace

// Review: --window 0, -3 or 1e12 (which overflowed static_cast<int>) gave exit
// 0 with MATLAB's heuristic window; --window 1.5 was cut to 1; a NaN
// --smoothing-factor was taken; --min-amplitude nan marked every trial
// low_amplitude.
TEST_CASE("feature options outside their range are refused with the option and the range (2)") {
    TempDir dir("rollsense-cli-feature-options");
    const fs::path ds = dir / "ds";
    const auto rec = run_rollsense("run " + shell_quoted(fs::path(ROLLSENSE_SOURCE_DIR) / "scripts" / "paper_experiment.lua") +
                                   " --set runs=1 --set objects=C1,P1 --set speeds=10 --set analyse=false --seed 11 "
                                   "--no-progress -q --out " + shell_quoted(ds));
    REQUIRE(rec.status == 0);
    const struct {
        const char* option;
        const char* says;
    } cases[] = {
        {"--window 0", "--window expects a whole number from 1 to 10000, got '0'"},
        {"--window -3", "--window expects a whole number from 1 to 10000, got '-3'"},
        {"--window 1e12", "--window expects a whole number from 1 to 10000, got '1e12'"},
        {"--window 1.5", "--window expects a whole number from 1 to 10000, got '1.5'"},
        {"--smoothing-factor nan", "--smoothing-factor must be a number within [0, 1], got NaN"},
        {"--smoothing-factor 1.5", "--smoothing-factor must be a number within [0, 1], got 1.5"},
        {"--peak-fraction nan", "--peak-fraction must be a number within (0, 1), got NaN"},
        {"--min-amplitude nan", "--min-amplitude must be a finite number >= 0, got NaN"},
        {"--min-amplitude -0.5", "--min-amplitude must be a finite number >= 0, got -0.5"},
        {"--min-amplitude inf", "--min-amplitude must be a finite number >= 0, got Inf"},
        {"--threads -1", "--threads expects a whole number from 0 to 4096, got '-1'"},
    };
    for (const auto& c : cases) {
        INFO(c.option);
        const auto out = dir / "f.csv";
        const auto r = run_rollsense("features " + shell_quoted(ds) + " -o " + shell_quoted(out) + " " + c.option);
        INFO(r.output);
        CHECK(r.status == 2);
        CHECK_THAT(r.output, Catch::Contains("rollsense features: " + std::string(c.says)));
        CHECK_FALSE(fs::exists(out));
    }
    // The other commands parse them in the same place.
    for (const std::string& command : {"evaluate " + shell_quoted(ds), "train " + shell_quoted(ds) + " -o " + shell_quoted(dir / "m.rsm")}) {
        const auto r = run_rollsense(command + " --window 0");
        INFO(r.output);
        CHECK(r.status == 2);
        CHECK_THAT(r.output, Catch::Contains("--window expects a whole number from 1 to 10000, got '0'"));
    }
    // In range they are taken: a fixed window of 7 samples is the one every channel used.
    const auto ok = run_rollsense("features " + shell_quoted(ds) + " -o " + shell_quoted(dir / "ok.csv") + " --window 7");
    INFO(ok.output);
    REQUIRE(ok.status == 0);
    CHECK_THAT(read_file(dir / "ok.csv"), Catch::Contains(",7,7,7,"));
}
