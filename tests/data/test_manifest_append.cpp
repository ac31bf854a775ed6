// Issue 25 item 1: recording whose cost is linear in the trials. The manifest
// is appended batch by batch (never rewritten), a crash while appending can
// leave a torn last line that the reader refuses and --resume cuts off, a
// failed append keeps no part of its rows, and samples are formatted with
// std::to_chars byte for byte as the "%.9g" of earlier datasets.
#include <catch2/catch.hpp>

#include <sys/resource.h>
#include <sys/stat.h>

#include <csignal>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "rollsense/csv.hpp"
#include "rollsense/dataset.hpp"
#include "log_capture.hpp"
#include "temp_dir.hpp"
#include "tiny_dataset.hpp"

using namespace rollsense;
using rollsense::testing::LogCapture;
using rollsense::testing::TempDir;
using rollsense::testing::tiny_info;
using rollsense::testing::tiny_record;
using rollsense::testing::tiny_samples;

namespace {

// Records trials t0..t<n-1>, `commit_every` per batch.
void record_trials(const std::filesystem::path& dir, int n, std::size_t commit_every,
                   DatasetOpenMode mode = DatasetOpenMode::create) {
    auto w = DatasetWriter::open(dir, tiny_info(), mode);
    REQUIRE(w.ok());
    (*w)->set_commit_every(commit_every);
    for (int i = 0; i < n; ++i) {
        const std::string id = "t" + std::to_string(i);
        if (!(*w)->has_trial(id)) REQUIRE((*w)->add_trial(tiny_record(id), tiny_samples()).ok());
    }
    REQUIRE((*w)->flush().ok());
}

ino_t inode(const std::filesystem::path& file) {
    struct stat st {};
    REQUIRE(::stat(file.c_str(), &st) == 0);
    return st.st_ino;
}

std::string printf_9g(double v) {
    char buf[64];
    const int n = std::snprintf(buf, sizeof buf, "%.9g", v);
    return std::string(buf, static_cast<std::size_t>(n));
}

}  // namespace

TEST_CASE("format_sample writes exactly what \"%.9g\" wrote, for random and edge values", "[data][format]") {
    std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.1, 1e-4, 9.99999999e-5, 1e-5, 123456789.0, 1234567890.0,
                                  999999999.0, 999999999.5, 1e9, 1e100, -1e-100, 5e-324, 2.2250738585072014e-308,
                                  std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), 44.0,
                                  -44.0, 0.00102348, 0.5, 2.5, 1.0000000005, 100.0, 1e21, 1e22, 123.456,
                                  // exact ties at the 10th digit (rounded half to even), the fast range's ends
                                  1234567.125, 1234567.375, -12345678.5, 12345679.5, 999999999.7, 1e-11, 9.99999999e-12,
                                  std::nextafter(1e9, 0.0), std::nextafter(1e-11, 0.0), 0.0001, 9.9999999995e-5};
    std::mt19937_64 rng(25);
    std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
    std::uniform_int_distribution<int> exponent(-320, 308);
    std::uniform_int_distribution<std::uint64_t> bits;
    for (int i = 0; i < 200000; ++i) {
        values.push_back(mantissa(rng) * std::pow(10.0, exponent(rng) % 40));  // the sensor's range and beyond
        values.push_back(std::ldexp(mantissa(rng), exponent(rng) * 3));       // every binary exponent
        double any;
        const std::uint64_t b = bits(rng);
        std::memcpy(&any, &b, sizeof any);  // any bit pattern (NaN and Inf excepted below)
        values.push_back(any);
        values.push_back(static_cast<double>(static_cast<std::int64_t>(b >> 20)) - 8e12);  // whole numbers
    }
    std::size_t differ = 0;
    for (double v : values) {
        if (!std::isfinite(v)) continue;
        if (csv::format_sample(v) != printf_9g(v) && ++differ <= 5)
            FAIL_CHECK(std::hexfloat << v << ": to_chars '" << csv::format_sample(v) << "', printf '" << printf_9g(v)
                                     << "'");
    }
    CHECK(differ == 0);
    CHECK(csv::format_sample(std::numeric_limits<double>::quiet_NaN()) == "NaN");
    CHECK(csv::format_sample(-std::numeric_limits<double>::infinity()) == "-Inf");
    CHECK(csv::format_sample(1e-5) == "1e-05");
    CHECK(csv::format_sample(-0.0) == "-0");
}

TEST_CASE("append_sample returns, bit for bit, what its text reads back as", "[data][format]") {
    std::mt19937_64 rng(26);
    std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
    std::uniform_int_distribution<int> exponent(-14, 11);
    std::vector<double> values = {1234567.125, -12345678.5, 999999999.7, 1e-11, 0.0, -0.0, 1e300, 5e-324,
                                  std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
    for (int i = 0; i < 200000; ++i) values.push_back(mantissa(rng) * std::pow(10.0, exponent(rng)));
    std::size_t differ = 0;
    for (double v : values) {
        std::string out = "x,";
        const double back = csv::append_sample(out, v);
        const double parsed = csv::parse_number(std::string_view(out).substr(2), "test").value();
        if (std::memcmp(&back, &parsed, sizeof back) != 0 && ++differ <= 5)
            FAIL_CHECK(std::hexfloat << v << " written as '" << out << "': returned " << back << ", parsed " << parsed);
    }
    CHECK(differ == 0);
}

TEST_CASE("the manifest is appended batch by batch, never rewritten, and equals one written whole",
          "[data][manifest]") {
    TempDir dir;
    auto w = DatasetWriter::open(dir.path() / "ds", tiny_info(), DatasetOpenMode::create);
    REQUIRE(w.ok());
    (*w)->set_commit_every(2);
    const auto manifest = dir.path() / "ds" / "manifest.csv";
    const ino_t first = inode(manifest);
    std::uintmax_t size = std::filesystem::file_size(manifest);
    for (int i = 0; i < 6; ++i) {
        REQUIRE((*w)->add_trial(tiny_record("t" + std::to_string(i)), tiny_samples()).ok());
        REQUIRE((*w)->flush().ok());
        CHECK(inode(manifest) == first);  // the same file, grown (a rewrite renames a new one over it)
        CHECK(std::filesystem::file_size(manifest) > size);
        size = std::filesystem::file_size(manifest);
        CHECK((*w)->has_trial("t" + std::to_string(i)));
        CHECK_FALSE((*w)->has_trial("t" + std::to_string(i + 1)));
    }
    w->reset();
    // Byte-identical to the same trials committed in other batch sizes.
    TempDir other;
    record_trials(other.path() / "ds", 6, 64);
    CHECK(testing::read_file(manifest) == testing::read_file(other.path() / "ds" / "manifest.csv"));
    auto back = DatasetReader::open(dir.path() / "ds");
    REQUIRE(back.ok());
    CHECK(back->trials().size() == 6);
}

TEST_CASE("a torn last manifest line is refused by the reader and cut off by --resume", "[data][manifest][resume]") {
    TempDir whole, torn;
    record_trials(whole.path() / "ds", 4, 1);
    record_trials(torn.path() / "ds", 3, 1);
    const auto manifest = torn.path() / "ds" / "manifest.csv";
    // A crash in the middle of appending t3's row: its file is durable, its row half there.
    std::filesystem::copy_file(whole.path() / "ds" / "trials" / "t3.csv", torn.path() / "ds" / "trials" / "t3.csv");
    const std::string full = testing::read_file(whole.path() / "ds" / "manifest.csv");
    const std::string before = testing::read_file(manifest);
    REQUIRE(full.rfind(before, 0) == 0);
    testing::write_file(manifest, before + full.substr(before.size(), 9));  // "t3,trials" and no line end

    auto refused = DatasetReader::open(torn.path() / "ds");
    REQUIRE_FALSE(refused.ok());
    // Review: "Continue the run with --resume" was ambiguous where the dataset is a replay's source.
    const std::string ds = (torn.path() / "ds").string();
    CHECK_THAT(refused.error().message, Catch::Contains("manifest.csv:5: the last row has no line end") &&
                                            Catch::Contains("Continue the run that recorded " + ds +
                                                            " with --resume --out " + ds));

    SECTION("resuming cuts the line and records the trial again: the dataset of an uninterrupted run") {
        record_trials(torn.path() / "ds", 4, 1, DatasetOpenMode::resume);
        CHECK(testing::read_file(manifest) == full);
        CHECK(testing::read_file(torn.path() / "ds" / "trials" / "t3.csv") ==
              testing::read_file(whole.path() / "ds" / "trials" / "t3.csv"));
        auto back = DatasetReader::open(torn.path() / "ds");
        REQUIRE(back.ok());
        CHECK(back->trials().size() == 4);
    }
    SECTION("a torn header (a crash before the first row) is cut too") {
        testing::write_file(manifest, "trial_id,fi");
        record_trials(torn.path() / "ds", 4, 2, DatasetOpenMode::resume);
        CHECK(testing::read_file(manifest) == full);
    }
}

TEST_CASE("a manifest cut just after a line end inside a quoted extra value is torn too", "[data][manifest][resume]") {
    // A row whose `extra` holds a line end is written quoted over two lines; a
    // crash right after that inner line end leaves a file ending in '\n' with
    // the quote still open.
    const auto record = [](const std::filesystem::path& dir, int n, DatasetOpenMode mode) {
        auto w = DatasetWriter::open(dir, tiny_info(), mode);
        REQUIRE(w.ok());
        (*w)->set_commit_every(1);
        for (int i = 0; i < n; ++i) {
            auto rec = tiny_record("t" + std::to_string(i));
            rec.info.extra["note"] = "first line\nsecond line";
            if (!(*w)->has_trial(rec.info.id)) REQUIRE((*w)->add_trial(rec, tiny_samples()).ok());
        }
        REQUIRE((*w)->flush().ok());
    };
    TempDir whole, torn;
    record(whole.path() / "ds", 3, DatasetOpenMode::create);
    record(torn.path() / "ds", 2, DatasetOpenMode::create);
    const auto manifest = torn.path() / "ds" / "manifest.csv";
    std::filesystem::copy_file(whole.path() / "ds" / "trials" / "t2.csv", torn.path() / "ds" / "trials" / "t2.csv");
    const std::string full = testing::read_file(whole.path() / "ds" / "manifest.csv");
    const std::string before = testing::read_file(manifest);
    const auto inner = full.find("first line\n", before.size());
    REQUIRE(inner != std::string::npos);
    testing::write_file(manifest, full.substr(0, inner + 11));  // t2's row up to its inner line end
    auto refused = DatasetReader::open(torn.path() / "ds");
    REQUIRE_FALSE(refused.ok());
    CHECK_THAT(refused.error().message, Catch::Contains("manifest.csv:6: the last row has no line end"));
    record(torn.path() / "ds", 3, DatasetOpenMode::resume);
    CHECK(testing::read_file(manifest) == full);
    auto back = DatasetReader::open(torn.path() / "ds");
    REQUIRE(back.ok());
    CHECK(back->trials().size() == 3);
    CHECK(back->trials().back().info.extra.at("note") == "first line\nsecond line");
}

TEST_CASE("mount and index_in_mount have manifest columns of their own, reading puts them back", "[data][manifest]") {
    TempDir dir;
    {
        auto w = DatasetWriter::open(dir.path() / "ds", tiny_info(), DatasetOpenMode::create);
        REQUIRE(w.ok());
        auto mounted = tiny_record("t0");
        mounted.info.extra = {{"mount", "C1-1"}, {"index_in_mount", "4"}, {"operator", "ab"}};
        REQUIRE((*w)->add_trial(mounted, tiny_samples()).ok());
        REQUIRE((*w)->add_trial(tiny_record("t1"), tiny_samples()).ok());  // no protocol: empty cells
        auto semicolon = tiny_record("t2");
        semicolon.info.extra = {{"mount", "rig;2"}};  // its own column: read back the same
        REQUIRE((*w)->add_trial(semicolon, tiny_samples()).ok());
        REQUIRE((*w)->flush().ok());
    }
    const std::string text = testing::read_file(dir.path() / "ds" / "manifest.csv");
    CHECK(text.rfind("trial_id,file,object,speed,repetition,seed,samples,invalid_samples,mount,index_in_mount,extra\n", 0) == 0);
    CHECK(text.find(",C1-1,4,operator=ab\n") != std::string::npos);
    CHECK(text.find(",,,\n") != std::string::npos);
    auto back = DatasetReader::open(dir.path() / "ds");
    REQUIRE(back.ok());
    CHECK(back->trials()[0].info.extra ==
          std::map<std::string, std::string>{{"index_in_mount", "4"}, {"mount", "C1-1"}, {"operator", "ab"}});
    CHECK(back->trials()[1].info.extra.empty());
    CHECK(back->trials()[2].info.extra == std::map<std::string, std::string>{{"mount", "rig;2"}});
    // A manifest of an earlier version kept them in `extra`: read the same.
    testing::write_file(dir.path() / "ds" / "manifest.csv",
                        "trial_id,file,object,speed,repetition,seed,samples,invalid_samples,extra\n"
                        "t0,trials/t0.csv,C1,10,1,0,0,0,index_in_mount=4;mount=C1-1;operator=ab\n");
    auto earlier = DatasetReader::open(dir.path() / "ds");
    REQUIRE(earlier.ok());
    CHECK(earlier->trials()[0].info.extra == back->trials()[0].info.extra);
}

TEST_CASE("a hand-made manifest without a final line end is read as before", "[data][manifest]") {
    TempDir dir;
    std::filesystem::create_directories(dir.path() / "trials");
    testing::write_file(dir.path() / "trials" / "a.csv", "time,ch1\n0,1\n0.1,2\n");
    testing::write_file(dir.path() / "manifest.csv", "trial_id,file,object,speed,repetition,samples\n"
                                                     "a,trials/a.csv,C1,10,1,2");  // no dataset-info.csv
    auto ds = DatasetReader::open(dir.path());
    REQUIRE(ds.ok());
    CHECK(ds->trials().size() == 1);
}

TEST_CASE("a failed manifest append keeps no part of its rows", "[data][manifest]") {
    TempDir dir;
    auto w = DatasetWriter::open(dir.path() / "ds", tiny_info(), DatasetOpenMode::create);
    REQUIRE(w.ok());
    (*w)->set_commit_every(1);
    REQUIRE((*w)->add_trial(tiny_record("t0"), tiny_samples()).ok());
    REQUIRE((*w)->flush().ok());
    const auto manifest = dir.path() / "ds" / "manifest.csv";
    const std::string before = testing::read_file(manifest);
    // A file-size limit a few bytes beyond the manifest: t1's small trial file
    // fits, its manifest row does not (a write cut short, as on a full disk).
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit old{};
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &old) == 0);
    rlimit small = old;
    small.rlim_cur = before.size() + 10;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
    REQUIRE((*w)->add_trial(tiny_record("t1"), tiny_samples()).ok());
    const auto s = (*w)->flush();
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &old) == 0);
    std::signal(SIGXFSZ, old_handler);
    REQUIRE_FALSE(s.ok());
    CHECK_THAT(s.message(), Catch::Contains("manifest.csv: write failed") && Catch::Contains("not saved: t1") &&
                                Catch::Contains("1 trial(s) are safely in"));
    CHECK(testing::read_file(manifest) == before);
    {
        // Review finding 9: the caller told of the failure reports it; closing the writer does not log it again.
        const LogCapture log;
        w->reset();
        CHECK(log.lines().empty());
    }
    auto back = DatasetReader::open(dir.path() / "ds");
    REQUIRE(back.ok());
    CHECK(back->trials().size() == 1);
}

TEST_CASE("a write failure no caller was told of is logged once when the writer closes", "[data][manifest]") {
    TempDir dir;
    auto w = DatasetWriter::open(dir.path() / "ds", tiny_info(), DatasetOpenMode::create);
    REQUIRE(w.ok());
    (*w)->set_commit_every(1);
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit old{};
    REQUIRE(::getrlimit(RLIMIT_FSIZE, &old) == 0);
    rlimit small = old;
    small.rlim_cur = testing::read_file(dir.path() / "ds" / "manifest.csv").size() + 10;
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
    const LogCapture log;
    REQUIRE((*w)->add_trial(tiny_record("t0"), tiny_samples()).ok());
    w->reset();
    REQUIRE(::setrlimit(RLIMIT_FSIZE, &old) == 0);
    std::signal(SIGXFSZ, old_handler);
    REQUIRE(log.lines().size() == 1);
    CHECK_THAT(log.lines()[0], Catch::Contains("write failed") && Catch::Contains("not saved: t0"));
}
