// Bad data gets a clear error naming the file, the line and the column: each
// kind of malformed dataset, and the message the replay gives for it.
#include <catch2/catch.hpp>

#include <fstream>

#include "replay_fixture.hpp"

using namespace rollsense;

namespace {

const char* kManifest =
    "trial_id,file,object,speed,repetition,samples\n"
    "t1,trials/t1.csv,C1,10,1,3\n";

// The error the replay gives for a dataset: at configure, or when trial t1 begins.
std::string replay_error(const rt::TempDir& dir) {
    auto s = rt::open_replay(dir / "ds");
    if (!s) return s.error().message;
    auto st = (*s)->begin_trial(rt::script_trial("C1", "10", 1));
    return st.ok() ? std::string("no error") : st.message();
}

std::string trial_file(const rt::TempDir& dir) { return (dir / "ds/trials/t1.csv").string(); }

}  // namespace

TEST_CASE("malformed datasets: missing files", "[replay][malformed]") {
    rt::TempDir dir;
    SECTION("no dataset folder") {
        auto msg = replay_error(dir);
        CHECK(msg == "cannot replay dataset '" + (dir / "ds").string() + "': " + (dir / "ds").string() +
                         ": no such dataset folder");
    }
    SECTION("a file where the dataset folder should be") {  // user review: a features CSV was "no such folder"
        std::ofstream(dir / "ds") << "trial_id,object\n";
        CHECK_THAT(replay_error(dir), Catch::EndsWith(": a file, not a dataset folder (give the folder a run recorded)"));
    }
    SECTION("a relative path names the working directory it was taken from") {
        auto params = rt::replay_params("no/such/dataset");
        REQUIRE(params.ok());
        plugins::replay::ReplaySensor s;
        auto st = s.on_configure(*params, {});
        REQUIRE_FALSE(st.ok());
        CHECK(st.message().find("cannot replay dataset 'no/such/dataset' (relative to the working directory " +
                                std::filesystem::current_path().string() + ")") == 0);
    }
    SECTION("no manifest") {
        std::filesystem::create_directories(dir / "ds/trials");
        CHECK(replay_error(dir).find((dir / "ds").string() + " holds no dataset (no manifest.csv): give a folder that "
                                     "'rollsense run ... --out DIR' recorded") != std::string::npos);
        // Review (bad input) item 8: a dataset that lost only its manifest is said to, not to be no dataset.
        rt::write_file(dir / "ds/dataset-info.csv", "key,value\nformat,rollsense-dataset\n");
        CHECK(replay_error(dir).find((dir / "ds").string() + " has a dataset-info.csv but no manifest.csv, the list of "
                                     "its trials: restore it") != std::string::npos);
    }
    SECTION("the manifest points at a missing trial file") {
        rt::write_file(dir / "ds/manifest.csv", std::string(kManifest) + "t2,trials/t2.csv,C1,10,2,3\n");
        rt::write_file(dir / "ds/trials/t1.csv", "time,ch1,ch2,ch3\n0,1,2,3\n0.1,1,2,3\n0.2,1,2,3\n");
        CHECK(replay_error(dir).find((dir / "ds/manifest.csv").string() +
                                     ":3: trial 't2' is listed, but " + (dir / "ds/trials/t2.csv").string() +
                                     " is missing. Put the file back, or delete line 3 of manifest.csv") != std::string::npos);
    }
    SECTION("an empty dataset parameter") {
        auto params = rt::replay_params("");
        REQUIRE(params.ok());
        plugins::replay::ReplaySensor s;
        CHECK(s.on_configure(*params, {}).message().find("parameter 'dataset' is empty") == 0);
    }
    SECTION("no dataset parameter at all: the schema refuses the profile") {
        auto p = validate_params(plugins::replay::replay_schema(), {}, "share/profiles/replay.lua: devices.tactile");
        REQUIRE_FALSE(p.ok());
        CHECK(p.error().message.find("dataset") != std::string::npos);
    }
}

TEST_CASE("malformed datasets: bad manifests", "[replay][malformed]") {
    rt::TempDir dir;
    rt::write_file(dir / "ds/trials/t1.csv", "time,ch1,ch2,ch3\n0,1,2,3\n0.1,1,2,3\n0.2,1,2,3\n");
    const std::string manifest = (dir / "ds/manifest.csv").string();
    SECTION("a required column missing") {
        rt::write_file(dir / "ds/manifest.csv", "trial_id,file,object,speed,repetition\nt1,trials/t1.csv,C1,10,1\n");
        CHECK(replay_error(dir).find(manifest + ":1: no column 'samples' in the header") != std::string::npos);
    }
    SECTION("a repetition that is not a whole number") {
        rt::write_file(dir / "ds/manifest.csv", "trial_id,file,object,speed,repetition,samples\nt1,trials/t1.csv,C1,10,one,3\n");
        CHECK(replay_error(dir).find(manifest + ":2: column 'repetition': 'one' is not a whole number") != std::string::npos);
    }
    SECTION("the same trial id twice") {
        rt::write_file(dir / "ds/manifest.csv", std::string(kManifest) + "t1,trials/t1.csv,C1,10,2,3\n");
        CHECK(replay_error(dir).find(manifest + ":3: column 'trial_id': trial id 't1' appears twice") !=
              std::string::npos);
    }
    // Review (data): one file listed twice sat in two folds at once.
    SECTION("one trial file named by two trials") {
        rt::write_file(dir / "ds/manifest.csv", std::string(kManifest) + "t2,trials/./t1.csv,C1,10,2,3\n");
        CHECK(replay_error(dir).find(manifest + ":3: column 'file': trial 't2' names the file trials/./t1.csv, which "
                                                "trial 't1' names too") != std::string::npos);
    }
    SECTION("no trials") {
        rt::write_file(dir / "ds/manifest.csv", "trial_id,file,object,speed,repetition,samples\n");
        CHECK(replay_error(dir).find(manifest + ": lists no trials") != std::string::npos);
    }
}

TEST_CASE("malformed datasets: bad trial files", "[replay][malformed]") {
    rt::TempDir dir;
    rt::write_file(dir / "ds/manifest.csv", kManifest);
    auto trial = [&](const std::string& text) { rt::write_file(dir / "ds/trials/t1.csv", text); };
    const std::string file = trial_file(dir);
    const std::string header = "time,ch1,ch2,ch3\n";
    // Hand-made datasets take their channels from the first trial file; a
    // dataset-info.csv fixes them. Both must reject the same files.
    const bool with_info = GENERATE(false, true);
    if (with_info)
        rt::write_file(dir / "ds/dataset-info.csv",
                       "key,value\nformat,rollsense-dataset\nformat_version,1\nsample_rate_hz,10\nchannels,ch1 ch2 ch3\n"
                       "joints,\nseed,3\n");
    INFO("with dataset-info.csv: " << with_info);

    SECTION("a well-formed file plays") {
        trial(header + "0,1,2,3\n0.1,1,2,3\n0.2,1,2,3\n");
        CHECK(replay_error(dir) == "no error");
    }
    SECTION("a truncated row") {
        trial(header + "0,1,2,3\n0.1,1,2,3\n0.2,1\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":4: 2 fields, the header has 4 (a truncated or malformed row)");
    }
    SECTION("a truncated file: fewer rows than the manifest says") {
        trial(header + "0,1,2,3\n0.1,1,2,3\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ": 2 samples, the manifest says 3 (a truncated file?)");
    }
    SECTION("a quoted field left open at the end") {
        trial(header + "0,1,2,3\n0.1,1,2,3\n0.2,1,2,\"3\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":4: a quoted field is not closed before the end of the file");
    }
    SECTION("a value that is not a number") {
        trial(header + "0,1,2,3\n0.1,1,2.5.1,3\n0.2,1,2,3\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":3: column 'ch2': '2.5.1' is not a number");
    }
    SECTION("an empty value") {
        trial(header + "0,1,2,3\n0.1,1,2,3\n0.2,,2,3\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":4: column 'ch1': empty field where a number is expected");
    }
    SECTION("time that does not increase") {
        trial(header + "0,1,2,3\n0.2,1,2,3\n0.1,1,2,3\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":4: column 'time': time 0.1 does not increase (previous 0.2)");
    }
    SECTION("a time that is not finite") {
        trial(header + "0,1,2,3\nNaN,1,2,3\n0.2,1,2,3\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":3: column 'time': time must be a finite number");
    }
    SECTION("no time column") {
        trial("t,ch1,ch2,ch3\n0,1,2,3\n0.1,1,2,3\n0.2,1,2,3\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":1: no column 'time' in the header (columns: t, ch1, ch2, ch3)");
    }
    SECTION("a valid flag that is not 0 or 1") {
        trial("time,ch1,ch2,ch3,valid\n0,1,2,3,1\n0.1,1,2,3,yes\n0.2,1,2,3,1\n");
        CHECK(replay_error(dir) == "trial 't1': " + file + ":3: column 'valid': 'yes' is not 0 or 1");
    }
}

TEST_CASE("malformed datasets: the wrong number of channels", "[replay][malformed]") {
    rt::TempDir dir;
    rt::write_file(dir / "ds/manifest.csv", std::string(kManifest) + "t2,trials/t2.csv,C1,10,2,3\n");
    rt::write_file(dir / "ds/trials/t1.csv", "time,ch1,ch2,ch3\n0,1,2,3\n0.1,1,2,3\n0.2,1,2,3\n");
    const std::string file2 = (dir / "ds/trials/t2.csv").string();
    auto second_trial_error = [&] {
        auto s = rt::open_replay(dir / "ds");
        if (!s) return s.error().message;
        auto st = (*s)->begin_trial(rt::script_trial("C1", "10", 2));
        return st.ok() ? std::string("no error") : st.message();
    };
    SECTION("a channel fewer than the dataset's") {
        rt::write_file(dir / "ds/trials/t2.csv", "time,ch1,ch2\n0,1,2\n0.1,1,2\n0.2,1,2\n");
        CHECK(second_trial_error() == "trial 't2': " + file2 +
                                          ":1: no column 'ch3' in the header (columns: time, ch1, ch2) — the dataset "
                                          "has 3 channels");
    }
    SECTION("a channel more than the dataset's") {
        rt::write_file(dir / "ds/trials/t2.csv", "time,ch1,ch2,ch3,ch4\n0,1,2,3,4\n0.1,1,2,3,4\n0.2,1,2,3,4\n");
        CHECK(second_trial_error() == "trial 't2': " + file2 +
                                          ":1: column 'ch4' is not a channel of this dataset, which has 3 (ch1 ch2 "
                                          "ch3): a file from another setup?");
    }
    SECTION("no channel at all") {
        rt::write_file(dir / "ds/manifest.csv", kManifest);
        rt::write_file(dir / "ds/trials/t1.csv", "time,p1,p2\n0,1,2\n0.1,1,2\n0.2,1,2\n");
        CHECK(second_trial_error().find(": no sensor channel columns (hand-made trial files name them ch1, ch2, ...") !=
              std::string::npos);
    }
}

// Review: a misspelt check_joint finished "done" with only an info line, the
// roll never checked. Only the default may find no column, where the dataset
// has nothing to check (hand-made, or no joint recorded).
TEST_CASE("check_joint must name a joint column the dataset recorded", "[replay][malformed]") {
    rt::TempDir dir;
    const std::string way_out = "name one with --set devices.tactile.params.check_joint=JOINT, or "
                                "--set devices.tactile.params.check_joint='' to replay without checking the roll";
    SECTION("a recorded dataset") {
        rt::write_dataset(dir / "ds", {rt::TrialSpec("C1", "10", 1, 5)});
        auto s = rt::open_replay(dir / "ds", {{"check_joint", std::string("nosuch")}});
        REQUIRE_FALSE(s.ok());
        CHECK(s.error().code == ErrorCode::invalid_argument);
        CHECK(s.error().message == "parameter 'check_joint' = 'nosuch': " + (dir / "ds").string() +
                                       " recorded no such joint column (its joint columns: sensing_finger); " + way_out);
        CHECK(rt::open_replay(dir / "ds").ok());
        CHECK(rt::open_replay(dir / "ds", {{"check_joint", std::string("")}}).ok());
    }
    SECTION("a recording whose hand names its finger otherwise") {
        rt::write_dataset(dir / "ds", {rt::TrialSpec("C1", "10", 1, 5)});
        auto info = rt::read_file(dir / "ds/dataset-info.csv");
        const auto at = info.find("sensing_finger");
        REQUIRE(at != std::string::npos);
        rt::write_file(dir / "ds/dataset-info.csv", info.replace(at, 14, "finger"));
        auto s = rt::open_replay(dir / "ds");
        REQUIRE_FALSE(s.ok());
        CHECK(s.error().message.find("'sensing_finger': " + (dir / "ds").string() +
                                     " recorded no such joint column (its joint columns: finger)") != std::string::npos);
        CHECK(rt::open_replay(dir / "ds", {{"check_joint", std::string("finger")}}).ok());
    }
    SECTION("a hand-made dataset without joint columns") {
        rt::write_file(dir / "ds/manifest.csv", kManifest);
        rt::write_file(dir / "ds/trials/t1.csv", "time,ch1,ch2,ch3\n0,1,2,3\n0.1,1,2,3\n0.2,1,2,3\n");
        rt::LogCapture log(LogLevel::info);
        CHECK(rt::open_replay(dir / "ds").ok());  // the default: not checked, said once
        CHECK(log.count("recorded no 'sensing_finger' column: the script's roll is not checked") == 1);
        auto s = rt::open_replay(dir / "ds", {{"check_joint", std::string("finger")}});
        REQUIRE_FALSE(s.ok());
        CHECK(s.error().message.find("'finger': " + (dir / "ds").string() +
                                     " recorded no such joint column (it recorded none); " + way_out) !=
              std::string::npos);
    }
}
