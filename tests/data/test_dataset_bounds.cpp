// Bounded reading of a dataset (issue 22, "bounded, checked parsing"): the
// manifest's sample count is a hint that must not size allocations, the
// sample rate must be a usable number, and a manifest names files inside its
// folder only. Each error names the file and line.
#include <catch2/catch.hpp>

#include <fstream>

#include "../bagged_trees/address_space_limit.hpp"
#include "rollsense/dataset.hpp"
#include "temp_dir.hpp"

using namespace rollsense;
using rollsense::testing::TempDir;

namespace {

const char* kInfo = "key,value\nformat,rollsense-dataset\nformat_version,1\nsample_rate_hz,31.1\nchannels,ch1\n"
                    "joints,\nprofile,test\nseed,1\n";

void write(const std::filesystem::path& f, const std::string& text) {
    std::filesystem::create_directories(f.parent_path());
    std::ofstream(f, std::ios::binary) << text;
}

std::string manifest(const std::string& file, const std::string& samples) {
    return "trial_id,file,object,speed,repetition,seed,samples,invalid_samples,extra\nt1," + file + ",C1,10,1,1," +
           samples + ",0,\n";
}

}  // namespace

TEST_CASE("a manifest claiming a billion samples does not size the trial's allocation", "[data][bounds]") {
    TempDir dir;
    write(dir / "ds" / "dataset-info.csv", kInfo);
    write(dir / "ds" / "manifest.csv", manifest("trials/t1.csv", "1000000000"));
    write(dir / "ds" / "trials" / "t1.csv", "time,ch1,valid\n0,1,1\n0.1,2,1\n");
    // On main this reserved 1e9 samples per column (24 GB) before reading a row.
    const auto outcome = rollsense::testing::run_with_address_space_limit(std::size_t{2} << 30, [&] {
        auto r = DatasetReader::open(dir / "ds");
        if (!r.ok()) return false;
        auto t = r->load(r->trials().front());
        return !t.ok() && t.error().message.find("2 samples, the manifest says 1000000000") != std::string::npos;
    });
    CHECK(outcome == rollsense::testing::ChildOutcome::passed);
}

TEST_CASE("a sample rate that is not a finite positive number is refused with file:line", "[data][bounds]") {
    for (const char* rate : {"NaN", "inf", "0", "-31.1", "1e300"}) {
        TempDir dir;
        std::string info = kInfo;
        info.replace(info.find("31.1"), 4, rate);
        write(dir / "ds" / "dataset-info.csv", info);
        write(dir / "ds" / "manifest.csv", manifest("trials/t1.csv", "2"));
        write(dir / "ds" / "trials" / "t1.csv", "time,ch1,valid\n0,1,1\n0.1,2,1\n");
        auto r = DatasetReader::open(dir / "ds");
        INFO(rate);
        REQUIRE_FALSE(r.ok());
        CHECK_THAT(r.error().message, Catch::Contains("dataset-info.csv:4: column 'value'") &&
                                          Catch::Contains("sample rate"));
    }
}

TEST_CASE("a manifest naming a file outside its folder is refused", "[data][bounds]") {
    for (const char* file : {"../outside.csv", "/etc/passwd", "trials/../../outside.csv"}) {
        TempDir dir;
        write(dir / "outside.csv", "time,ch1,valid\n0,1,1\n");
        write(dir / "ds" / "dataset-info.csv", kInfo);
        write(dir / "ds" / "manifest.csv", manifest(file, "1"));
        auto r = DatasetReader::open(dir / "ds");
        INFO(file);
        REQUIRE_FALSE(r.ok());
        CHECK_THAT(r.error().message, Catch::Contains("manifest.csv:2: column 'file'") &&
                                          Catch::Contains("not a path inside the dataset folder"));
    }
}

// Found by fuzz_manifest: a hand-made dataset (no dataset-info.csv) whose first
// trial's file column names the trials folder. Reading the folder threw from
// inside the CSV reader's stream buffer, out of DatasetReader::open, and ended
// the program.
TEST_CASE("a manifest whose file names a folder is refused with an error, not a thrown exception", "[data][bounds]") {
    TempDir dir;
    write(dir / "ds" / "manifest.csv", manifest("trials", "207"));
    std::filesystem::create_directories(dir / "ds" / "trials");
    Result<DatasetReader> r = Error{ErrorCode::ok, ""};
    REQUIRE_NOTHROW(r = DatasetReader::open(dir / "ds"));
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().message.find((dir / "ds" / "trials").string() + ": is a folder, not a CSV file") !=
          std::string::npos);
}

// Review: a manifest.csv that is itself a folder, beside dataset-info.csv, was
// read whole for a torn last line and threw from the stream buffer
// ("unexpected error: basic_filebuf::underflow error reading the file: Is a
// directory", exit 1). Resuming reads it the same way.
TEST_CASE("a manifest.csv that is a folder is refused naming it, not thrown", "[data][bounds]") {
    for (const bool recorded : {true, false}) {
        INFO("dataset-info.csv beside it: " << recorded);
        TempDir dir;
        if (recorded) write(dir / "ds" / "dataset-info.csv", kInfo);
        std::filesystem::create_directories(dir / "ds" / "manifest.csv");
        Result<DatasetReader> r = Error{ErrorCode::ok, ""};
        REQUIRE_NOTHROW(r = DatasetReader::open(dir / "ds"));
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().code == ErrorCode::parse_error);
        CHECK(r.error().message == (dir / "ds" / "manifest.csv").string() + ": is a folder, not a CSV file");
    }
    TempDir dir;
    write(dir / "ds" / "dataset-info.csv", kInfo);
    std::filesystem::create_directories(dir / "ds" / "manifest.csv");
    DatasetInfo info;  // kInfo's setup, so that resume reaches the manifest
    info.channels = {"ch1"};
    info.sample_rate_hz = 31.1;
    info.profile = "test";
    info.seed = 1;
    Result<std::unique_ptr<DatasetWriter>> w = Error{ErrorCode::ok, ""};
    REQUIRE_NOTHROW(w = DatasetWriter::open(dir / "ds", info, DatasetOpenMode::resume));
    REQUIRE_FALSE(w.ok());
    CHECK_THAT(w.error().message, Catch::Contains((dir / "ds" / "manifest.csv").string() + ": is a folder, not a CSV file"));
}
