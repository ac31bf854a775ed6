// What the feature extraction reads of a dataset (issue 24): which channels
// (named, never the first three by accident), which samples (invalid ones
// before and after the roll are not part of it), a bad trial file skipped
// with its reason instead of ending the extraction, the trials' extra
// metadata carried into features.csv, and a stop flag (Ctrl-C).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

#include "feature_fixtures.hpp"
#include "rollsense/features.hpp"

using namespace rollsense;
using namespace rollsense::features;
namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using test::temp_dir;
using test::triangle;

// Three clean peaks, 140 samples; channels `order` of the sensor's peaks
// (other columns flat noise-free zeros, which no peak rule accepts).
TrialData trial(std::size_t channels = 3, std::size_t first_peak_column = 0, std::size_t n = 140) {
    TrialData d;
    for (std::size_t i = 0; i < n; ++i) d.time.push_back(static_cast<double>(i) / 31.1);
    d.channels.assign(channels, std::vector<double>(n, 0.0));
    d.channels[first_peak_column] = triangle(n, 0.3, 40, 15, 20);
    d.channels[first_peak_column + 1] = triangle(n, 0.4, 60, 20, 15);
    d.channels[first_peak_column + 2] = triangle(n, 0.2, 80, 18, 18);
    d.joints = {std::vector<double>(n, 0.0)};
    d.valid.assign(n, 1);
    return d;
}

TrialRecord record(const std::string& id, const TrialData& d) {
    TrialRecord rec;
    rec.info.id = id;
    rec.info.object = "C1";
    rec.info.speed = "10";
    rec.info.repetition = 1;
    rec.samples = d.samples();
    return rec;
}

void write_dataset(const fs::path& dir, const DatasetInfo& info, const std::vector<std::pair<TrialRecord, TrialData>>& trials) {
    auto writer = DatasetWriter::open(dir, info, DatasetOpenMode::create);
    REQUIRE(writer.ok());
    for (const auto& [rec, d] : trials) REQUIRE((*writer)->add_trial(rec, d).ok());
    REQUIRE((*writer)->flush().ok());
}

DatasetInfo three_channels() {
    DatasetInfo info;
    info.channels = {"ch1", "ch2", "ch3"};
    info.joints = {"sensing_finger"};
    return info;
}

DatasetReader open(const fs::path& dir) {
    auto ds = DatasetReader::open(dir);
    INFO(ds.status().message());
    REQUIRE(ds.ok());
    return std::move(*ds);
}

}  // namespace

TEST_CASE("a trial file that cannot be read is skipped with its reason, the others are extracted",
          "[features][dataset][issue24]") {
    const auto dir = temp_dir("unreadable");
    write_dataset(dir, three_channels(), {{record("a", trial()), trial()}, {record("b", trial()), trial()},
                                          {record("c", trial()), trial()}});
    // Break trial b: a value that is not a number on its third line.
    {
        std::ifstream in(dir / "trials" / "b.csv");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const auto line3 = text.find('\n', text.find('\n') + 1) + 1;
        text.replace(line3, text.find(',', line3) - line3, "0.06x");
        std::ofstream(dir / "trials" / "b.csv") << text;
    }
    auto rows = extract_dataset(open(dir), {}, 2);
    INFO(rows.status().message());
    REQUIRE(rows.ok());
    REQUIRE(rows->size() == 3);
    CHECK((*rows)[0].clean);
    CHECK((*rows)[2].clean);
    const FeatureRow& b = (*rows)[1];
    CHECK(b.trial_id == "b");
    CHECK_FALSE(b.clean);
    CHECK_THAT(b.reason, Catch::StartsWith("unreadable (") && Catch::Contains("b.csv:3") &&
                             Catch::Contains("'0.06x' is not a number"));
    // It stays a row of features.csv, with the reason and no features.
    CHECK_THAT(format_features_csv(*rows), Catch::Contains("\nb,C1,10,1,0,unreadable ("));
    fs::remove_all(dir);
}

TEST_CASE("invalid samples after the recording's end do not reject a trial, one inside the roll still does",
          "[features][dataset][issue24]") {
    const auto dir = temp_dir("edges");
    const TrialData plain = trial();
    // A replay that recorded 12 reads past its recording: invalid NaN rows at the end.
    TrialData tail = plain;
    for (int k = 0; k < 12; ++k) {
        tail.time.push_back(tail.time.back() + 1.0 / 31.1);
        for (auto& c : tail.channels) c.push_back(kNaN);
        tail.joints[0].push_back(0.0);
        tail.valid.push_back(0);
    }
    // ...and invalid rows before the roll.
    TrialData head = plain;
    for (std::size_t i = 0; i < 3; ++i) {
        for (auto& c : head.channels) c[i] = kNaN;
        head.valid[i] = 0;
    }
    // An isolated failed read in the middle of the peaks, as a recording may have it.
    TrialData middle = plain;
    for (auto& c : middle.channels) c[60] = kNaN;
    middle.valid[60] = 0;
    write_dataset(dir, three_channels(), {{record("plain", plain), plain}, {record("tail", tail), tail},
                                          {record("head", head), head}, {record("middle", middle), middle}});
    auto rows = extract_dataset(open(dir), {}, 1);
    REQUIRE(rows.ok());
    REQUIRE(rows->size() == 4);
    const auto& p = (*rows)[0];
    REQUIRE(p.clean);
    for (std::size_t r : {1u, 2u}) {
        INFO((*rows)[r].trial_id << ": " << (*rows)[r].reason);
        CHECK((*rows)[r].clean);
        for (std::size_t k = 0; k < kFeatureCount; ++k) CHECK((*rows)[r].values[k] == Approx(p.values[k]).margin(1e-12));
    }
    CHECK_FALSE((*rows)[3].clean);
    CHECK_THAT((*rows)[3].reason, Catch::Contains("not_finite"));
    fs::remove_all(dir);
}

TEST_CASE("with more than three channels the identification channels must be named", "[features][dataset][issue24]") {
    const auto dir = temp_dir("channels");
    DatasetInfo info;
    info.channels = {"a_ch1", "a_ch2", "a_ch3", "b_ch1", "b_ch2", "b_ch3"};
    info.joints = {"sensing_finger"};
    const TrialData d = trial(6, 3);  // the peaks are on sensor b
    write_dataset(dir, info, {{record("t", d), d}});

    SECTION("unnamed: an error listing every channel and the way out, never the first three") {
        auto rows = extract_dataset(open(dir), {}, 1);
        REQUIRE_FALSE(rows.ok());
        CHECK(rows.error().code == ErrorCode::invalid_argument);
        CHECK_THAT(rows.error().message, Catch::Contains("6 sensor channels (a_ch1, a_ch2, a_ch3, b_ch1, b_ch2, b_ch3)") &&
                                             Catch::Contains("identification_channels"));
    }
    SECTION("named in dataset-info.csv: those three, in the order named") {
        std::ofstream(dir / "dataset-info.csv", std::ios::app) << "identification_channels,b_ch1 b_ch2 b_ch3\n";
        auto rows = extract_dataset(open(dir), {}, 1);
        INFO(rows.status().message());
        REQUIRE(rows.ok());
        CHECK((*rows)[0].clean);
    }
    SECTION("a name that is not a channel is an error naming it") {
        std::ofstream(dir / "dataset-info.csv", std::ios::app) << "identification_channels,b_ch1 b_ch2 c_ch3\n";
        auto rows = extract_dataset(open(dir), {}, 1);
        REQUIRE_FALSE(rows.ok());
        CHECK_THAT(rows.error().message, Catch::Contains("'c_ch3'"));
    }
    fs::remove_all(dir);
}

TEST_CASE("identification_channels picks the named columns of a trial", "[features][issue24]") {
    DatasetInfo info;
    info.channels = {"x", "y", "z", "w"};
    info.identification_channels = {"w", "x", "z"};
    auto c = identification_channels(info, "d");
    REQUIRE(c.ok());
    CHECK(*c == std::array<std::size_t, 3>{3, 0, 2});
    info.identification_channels = {"w", "x"};
    CHECK_FALSE(identification_channels(info, "d").ok());
    info.identification_channels.clear();
    info.channels = {"ch1", "ch2"};
    auto two = identification_channels(info, "d");
    REQUIRE_FALSE(two.ok());
    CHECK_THAT(two.error().message, Catch::Contains("2 sensor channels"));
}

TEST_CASE("a trial's extra metadata becomes extra_<key> columns of features.csv", "[features][csv][issue24]") {
    const auto dir = temp_dir("extra");
    TrialRecord a = record("a", trial()), b = record("b", trial());
    a.info.extra = {{"surface", "wood"}, {"operator", "kim"}};
    b.info.extra = {{"surface", "foam"}};
    write_dataset(dir, three_channels(), {{a, trial()}, {b, trial()}});
    auto rows = extract_dataset(open(dir), {}, 1);
    REQUIRE(rows.ok());
    const std::string csv = format_features_csv(*rows);
    const std::string header = csv.substr(0, csv.find('\n'));
    CHECK_THAT(header, Catch::EndsWith("window_ch3,extra_operator,extra_surface"));
    CHECK_THAT(csv, Catch::Contains(",kim,wood\n") && Catch::Contains(",,foam\n"));
    // And back.
    std::ofstream(dir / "f.csv") << csv;
    auto back = read_features_csv(dir / "f.csv");
    REQUIRE(back.ok());
    CHECK((*back)[0].extra == a.info.extra);
    CHECK((*back)[1].extra == b.info.extra);
    // Without extra metadata the file is as it always was: no extra columns.
    auto plain = *rows;
    for (auto& r : plain) r.extra.clear();
    CHECK_THAT(format_features_csv(plain).substr(0, 200), !Catch::Contains("extra_"));
    fs::remove_all(dir);
}

TEST_CASE("a set stop flag ends the extraction as cancelled", "[features][dataset][issue24]") {
    const auto dir = temp_dir("stop");
    write_dataset(dir, three_channels(), {{record("a", trial()), trial()}});
    std::atomic<bool> stop{true};
    auto rows = extract_dataset(open(dir), {}, 1, &stop);
    REQUIRE_FALSE(rows.ok());
    CHECK(rows.error().code == ErrorCode::cancelled);
    fs::remove_all(dir);
}
