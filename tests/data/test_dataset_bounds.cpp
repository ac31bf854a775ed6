// Bounded reading of a dataset (issue 22, "bounded, checked parsing"): the
// manifest's sample count is a hint that must not size allocations, the
// sample rate must be a usable number, and a manifest names files inside its
// folder only. Each error names the file and line.
#include <catch2/catch.hpp>

#include <fstream>

#include "../bagged_trees/address_space_limit.hpp"
#include "rollsense/csv.hpp"
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

// Review (bad input) item 2: a 20 MB line of commas took 1 GB (a std::string
// per empty field), and errors repeated a whole field or header, 5 MB of text
// for one long number. A record is bounded, and quoted text is cut.
TEST_CASE("a CSV record past its bounds is refused before it costs memory, and errors quote briefly", "[data][bounds]") {
    TempDir dir;
    write(dir / "ds" / "dataset-info.csv", kInfo);
    for (const auto& [line, says] : {std::pair{std::string(20'000'000, ','), "longer than 100000 fields"},
                                     std::pair{std::string(20'000'000, 'x'), "longer than 16777216 bytes"}}) {
        INFO(says);
        write(dir / "ds" / "manifest.csv", line + "\n");
        // 256 MB: on main the line of commas took 1 GB.
        const auto outcome = rollsense::testing::run_with_address_space_limit(std::size_t{256} << 20, [&] {
            auto r = DatasetReader::open(dir / "ds");
            return !r && r.status().message().find("manifest.csv:1: a record " + std::string(says)) != std::string::npos &&
                   r.status().message().size() < 400;
        });
        CHECK(outcome == rollsense::testing::ChildOutcome::passed);
    }
    // A header of 5,000 long names, and a 100,000-digit number with a stray byte: quoted, not repeated.
    std::string header = "trial_id";
    for (int i = 0; i < 5000; ++i) header += "," + std::string(100, 'h');
    write(dir / "ds" / "manifest.csv", header + "\n");
    auto r = DatasetReader::open(dir / "ds");
    REQUIRE_FALSE(r);
    CHECK_THAT(r.status().message(), Catch::Contains("(5001 columns)"));
    CHECK(r.status().message().size() < 4000);
    write(dir / "ds" / "manifest.csv", manifest("trials/t1.csv", std::string(100000, '7') + "\x01"));
    r = DatasetReader::open(dir / "ds");
    REQUIRE_FALSE(r);
    CHECK_THAT(r.status().message(), Catch::Contains("manifest.csv:2: column 'samples'") &&
                                         Catch::Contains("… (100001 bytes)"));
    CHECK(r.status().message().size() < 400);
    CHECK(csv::excerpt("a\x01\xff") == "a\\x01\\xff");
}

// Second review: the mark was found only before an unquoted first field (pandas' QUOTE_ALL quotes it).
TEST_CASE("a byte-order mark before a quoted first header field is read past", "[data][bounds]") {
    TempDir dir;
    write(dir / "f.csv", "\xEF\xBB\xBF\"trial_id\",\"x\"\n\"t1\",\"2\"\n");
    auto r = csv::Reader::open(dir / "f.csv");
    REQUIRE(r);
    CHECK(r->header() == std::vector<std::string>{"trial_id", "x"});
    write(dir / "g.csv", "ab\n");  // shorter than a mark: read from its start
    r = csv::Reader::open(dir / "g.csv");
    REQUIRE(r);
    CHECK(r->header() == std::vector<std::string>{"ab"});
}

// Review (bad input) items 5 and 6: a channel named twice in dataset-info.csv
// blamed every trial file, and a UTF-8 byte-order mark (Excel's "CSV UTF-8")
// made "no column 'trial_id' (columns: trial_id, ...)".
TEST_CASE("a column named twice in dataset-info.csv is refused there, a byte-order mark is read past", "[data][bounds]") {
    TempDir dir;
    write(dir / "ds" / "trials" / "t1.csv", "time,ch1,valid\n0,1,1\n0.1,2,1\n");
    write(dir / "ds" / "manifest.csv", "\xEF\xBB\xBF" + manifest("trials/t1.csv", "2"));
    write(dir / "ds" / "dataset-info.csv", kInfo);
    auto r = DatasetReader::open(dir / "ds");
    REQUIRE(r);
    CHECK(r->trials().front().info.id == "t1");
    std::string info = kInfo;
    info.replace(info.find("channels,ch1"), 12, "channels,ch1 ch2 ch1");
    write(dir / "ds" / "dataset-info.csv", info);
    r = DatasetReader::open(dir / "ds");
    REQUIRE_FALSE(r);
    CHECK_THAT(r.status().message(), Catch::Contains("dataset-info.csv:5: column 'value': channels names 'ch1' twice"));
    // Review (data): a key given twice was taken silently, the last one winning (here a sample rate appended).
    write(dir / "ds" / "dataset-info.csv", std::string(kInfo) + "sample_rate_hz,50\n");
    r = DatasetReader::open(dir / "ds");
    REQUIRE_FALSE(r);
    CHECK_THAT(r.status().message(), Catch::Contains("column 'key': 'sample_rate_hz' is given twice (first at line"));
    write(dir / "ds" / "run-info.csv", "key,value\nseed,1\nseed,2\n");
    const auto kv = csv::read_key_values(dir / "ds" / "run-info.csv");
    REQUIRE_FALSE(kv);
    CHECK_THAT(kv.error().message, Catch::Contains("run-info.csv:3: column 'key': 'seed' is given twice (first at line 2)"));
}
