// Whole numbers in data files are parsed strictly and range-checked: a value
// like 1e30 or inf is an error naming file, line and column, never a silent
// truncation or a float-to-integer conversion with undefined behaviour.
#include <catch2/catch.hpp>

#include "rollsense/csv.hpp"
#include "rollsense/dataset.hpp"
#include "rollsense/features.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::testing::TempDir;
using rollsense::testing::write_file;

namespace {
const char* kInfo =
    "key,value\nformat,rollsense-dataset\nversion,1\nsample_rate_hz,31.1\nchannels,ch1 ch2 ch3\n"
    "joints,sensing_finger\nprofile,sim\nseed,11\n";

std::string manifest_with(const std::string& repetition, const std::string& seed) {
    return "trial_id,file,object,speed,repetition,seed,samples,invalid_samples,extra\n"
           "C1-v10-r001,trials/C1-v10-r001.csv,C1,10," + repetition + "," + seed + ",0,0,\n";
}

// A one-trial dataset whose manifest row has these repetition and seed fields.
void write_dataset(const TempDir& dir, const std::string& info, const std::string& repetition,
                   const std::string& seed) {
    write_file(dir / "dataset-info.csv", info);
    write_file(dir / "manifest.csv", manifest_with(repetition, seed));
    write_file(dir / "trials/C1-v10-r001.csv", "time,ch1,ch2,ch3,sensing_finger,valid\n");
}
}  // namespace

TEST_CASE("whole-number fields: digits within the range, anything else names the place", "[data][csv]") {
    CHECK(*csv::parse_unsigned("42", 100, "f.csv:3: column 'n'") == 42);
    CHECK(*csv::parse_unsigned(" 7 ", 100, "here") == 7);
    CHECK(*csv::parse_integer("-5", -10, 10, "here") == -5);
    CHECK(*csv::parse_unsigned("18446744073709551615", UINT64_MAX, "here") == UINT64_MAX);
    for (const char* bad : {"1e30", "inf", "nan", "1.5", "-1", "+3", "", "0x10", "12abc"}) {
        auto v = csv::parse_unsigned(bad, UINT64_MAX, "f.csv:3: column 'n'");
        INFO(bad);
        REQUIRE_FALSE(v.ok());
        CHECK(v.error().code == ErrorCode::parse_error);
        CHECK_THAT(v.error().message, Catch::StartsWith("f.csv:3: column 'n'"));
    }
    auto over = csv::parse_unsigned("18446744073709551616", UINT64_MAX, "here");
    REQUIRE_FALSE(over.ok());
    CHECK_THAT(over.error().message, Catch::Contains("out of range"));
    auto above = csv::parse_integer("11", -10, 10, "here");
    REQUIRE_FALSE(above.ok());
    CHECK_THAT(above.error().message, Catch::Contains("[-10, 10]"));
}

TEST_CASE("a manifest seed of inf, 1e30 or beyond 64 bits is refused with file:line", "[data][manifest]") {
    for (const char* seed : {"inf", "1e30", "18446744073709551616", "-3"}) {
        TempDir dir;
        write_dataset(dir, kInfo, "1", seed);
        auto ds = DatasetReader::open(dir.path());
        INFO(seed);
        REQUIRE_FALSE(ds.ok());
        CHECK_THAT(ds.error().message, Catch::Contains("manifest.csv:2") && Catch::Contains("seed"));
    }
    TempDir dir;
    write_dataset(dir, kInfo, "1", "18446744073709551615");
    auto ds = DatasetReader::open(dir.path());
    INFO((ds.ok() ? std::string() : ds.error().message));
    REQUIRE(ds.ok());
    CHECK(ds->trials().at(0).info.seed == UINT64_MAX);
}

TEST_CASE("a repetition beyond int or a dataset-info seed of 1e30 is refused", "[data][manifest]") {
    {
        TempDir dir;
        write_dataset(dir, kInfo, "1e30", "5");
        auto ds = DatasetReader::open(dir.path());
        REQUIRE_FALSE(ds.ok());
        CHECK_THAT(ds.error().message, Catch::Contains("repetition"));
    }
    {
        TempDir dir;
        std::string info = kInfo;
        info.replace(info.find("seed,11"), 7, "seed,1e30");
        write_dataset(dir, info, "1", "5");
        auto ds = DatasetReader::open(dir.path());
        REQUIRE_FALSE(ds.ok());
        CHECK_THAT(ds.error().message, Catch::Contains("dataset-info.csv") && Catch::Contains("1e30"));
    }
}

TEST_CASE("a features file with a repetition of 1e30 is refused, not cast", "[data][features]") {
    TempDir dir;
    std::string header = "trial_id,object,speed,repetition,clean,reason";
    std::string row = "C1-v10-r001,C1,10,1e30,0,low_amplitude";
    for (int k = 1; k <= 13; ++k) {
        header += ",F" + std::to_string(k);
        row += ",";
    }
    write_file(dir / "features.csv", header + "\n" + row + "\n");
    auto back = features::read_features_csv(dir / "features.csv");
    REQUIRE_FALSE(back.ok());
    CHECK_THAT(back.error().message, Catch::Contains("features.csv:2") && Catch::Contains("repetition"));

    write_file(dir / "ok.csv", header + "\n" + "C1-v10-r001,C1,10,3,0,low_amplitude" + std::string(13, ',') + "\n");
    auto good = features::read_features_csv(dir / "ok.csv");
    REQUIRE(good.ok());
    CHECK(good->at(0).repetition == 3);
}
