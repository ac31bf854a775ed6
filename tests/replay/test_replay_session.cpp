// The replay plugin in real Sessions: scripts/paper_experiment.lua, unchanged,
// recorded on the mock hand and re-run on the replay profile gives the same
// trial files and the same features; playback timing on the virtual clock;
// a run with another seed; a bad trial file stops the run and loses nothing.
#include <catch2/catch.hpp>

#include <cmath>

#include "replay_fixture.hpp"
#include "rollsense/features.hpp"
#include "runtime/session/session.hpp"

using namespace rollsense;
namespace fs = std::filesystem;

namespace {

runtime::SessionOptions session_options(const fs::path& script, const std::string& profile, const fs::path& out,
                                        std::uint64_t seed, const std::vector<std::string>& settings) {
    runtime::SessionOptions o;
    o.script = script;
    o.profile = profile;
    o.share_dir = ROLLSENSE_SHARE_DIR;
    o.out_dir = out;
    o.seed = seed;
    o.plugin_path = {ROLLSENSE_PLUGIN_DIR};
    o.sandbox.max_slice_ms = 1000;
    for (const auto& kv : settings) REQUIRE(o.settings.add(kv).ok());
    return o;
}

runtime::RunSummary run(const runtime::SessionOptions& o) {
    runtime::Session session(o);
    return session.run();
}

const fs::path kPaperScript = fs::path(ROLLSENSE_SOURCE_DIR) / "scripts/paper_experiment.lua";
// Small enough to run in seconds, large enough for the script's 5-fold
// evaluation at its end (rs.analyse: features.csv, evaluation.txt, model).
const std::vector<std::string> kExperiment = {"runs=3", "objects=C1,P1", "speeds=10,20"};

std::vector<std::string> with(std::vector<std::string> a, const std::string& kv) {
    a.push_back(kv);
    return a;
}

DatasetReader open_dataset(const fs::path& dir) {
    auto r = DatasetReader::open(dir);
    INFO(r.status().message());
    REQUIRE(r.ok());
    return std::move(*r);
}

bool same_value(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// evaluation.txt without its wall-clock line ("evaluation took 0.3 s").
std::string evaluation_text(const fs::path& file) {
    std::string text = rt::read_file(file), out;
    std::size_t pos = 0;
    while (pos < text.size()) {
        auto end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(pos, end - pos);
        if (line.rfind("evaluation took", 0) != 0) out += line + "\n";
        pos = end + 1;
    }
    return out;
}

}  // namespace

TEST_CASE("paper_experiment.lua re-run on the replay profile reproduces the recording and its features",
          "[replay][session][roundtrip]") {
    rt::TempDir dir;
    // Record with the kernel: the mock hand and the example bump sensor.
    auto recorded = run(session_options(kPaperScript, "mock", dir / "recorded", 11, kExperiment));
    INFO(recorded.status.message());
    REQUIRE(recorded.status.ok());
    REQUIRE(recorded.trials_saved == 12);

    // Replay it through the same script with the recording's seed.
    rt::LogCapture log;
    auto replayed = run(session_options(kPaperScript, "replay", dir / "replayed", 11,
                                        with(kExperiment, "dataset=" + (dir / "recorded").string())));
    INFO(replayed.status.message());
    REQUIRE(replayed.status.ok());
    REQUIRE(replayed.trials_saved == 12);
    INFO(log.all());
    CHECK(log.lines().empty());  // no roll mismatch, no seed warning, nothing left unplayed

    // The trial files and the manifest are byte for byte the recording's.
    auto a = open_dataset(dir / "recorded");
    auto b = open_dataset(dir / "replayed");
    REQUIRE(a.trials().size() == b.trials().size());
    CHECK(rt::read_file(dir / "replayed/manifest.csv") == rt::read_file(dir / "recorded/manifest.csv"));
    for (const auto& t : a.trials()) {
        INFO(t.file);
        CHECK(rt::read_file(dir / "replayed" / t.file) == rt::read_file(dir / "recorded" / t.file));
    }

    // And so are the features the pipeline extracts from them.
    auto fa = features::extract_dataset(a, {}, 1);
    auto fb = features::extract_dataset(b, {}, 1);
    REQUIRE(fa.ok());
    REQUIRE(fb.ok());
    REQUIRE(fa->size() == 12);
    REQUIRE(fb->size() == fa->size());
    for (std::size_t i = 0; i < fa->size(); ++i) {
        const auto &x = (*fa)[i], &y = (*fb)[i];
        INFO(x.trial_id);
        CHECK(x.trial_id == y.trial_id);
        CHECK(x.object == y.object);
        CHECK(x.clean == y.clean);
        CHECK(x.reason == y.reason);
        for (std::size_t k = 0; k < features::kFeatureCount; ++k) CHECK(same_value(x.values[k], y.values[k]));
    }
    CHECK(features::format_features_csv(*fa) == features::format_features_csv(*fb));

    // The script's own analysis (rs.analyse at its end) agrees too: the same
    // features file, the same evaluation, and features equal to extracting
    // the recorded dataset directly.
    const std::string recorded_features = rt::read_file(dir / "recorded/features.csv");
    REQUIRE_FALSE(recorded_features.empty());
    CHECK(rt::read_file(dir / "replayed/features.csv") == recorded_features);
    CHECK(recorded_features == features::format_features_csv(*fa));
    const std::string recorded_evaluation = evaluation_text(dir / "recorded/evaluation.txt");
    REQUIRE_FALSE(recorded_evaluation.empty());
    CHECK(evaluation_text(dir / "replayed/evaluation.txt") == recorded_evaluation);
}

TEST_CASE("a replay with another seed plays by time and marks what the recording lacks",
          "[replay][session][seed]") {
    rt::TempDir dir;
    const std::vector<std::string> one = {"runs=3", "objects=C1", "speeds=20", "analyse=false"};
    REQUIRE(run(session_options(kPaperScript, "mock", dir / "recorded", 11, one)).status.ok());
    rt::LogCapture log;
    auto replayed = run(session_options(kPaperScript, "replay", dir / "replayed", 12,
                                        with(one, "dataset=" + (dir / "recorded").string())));
    INFO(replayed.status.message());
    REQUIRE(replayed.status.ok());
    INFO(log.all());
    CHECK(log.count("was recorded in a run with another --seed (the dataset's run seed is 11)") == 1);

    auto a = open_dataset(dir / "recorded");
    auto b = open_dataset(dir / "replayed");
    bool some_length_differs = false;
    for (std::size_t t = 0; t < a.trials().size(); ++t) {
        auto da = a.load(a.trials()[t]);
        auto db = b.load(b.trials()[t]);
        REQUIRE(da.ok());
        REQUIRE(db.ok());
        some_length_differs = some_length_differs || da->samples() != db->samples();
        for (std::size_t m = 0; m < db->samples(); ++m) {
            INFO(a.trials()[t].info.id << " sample " << m);
            if (m < da->samples()) {
                // Sample m of the replay is sample m of the recording: playback follows the clock.
                CHECK(db->channels[0][m] == da->channels[0][m]);
                CHECK(db->valid[m] == da->valid[m]);
            } else {
                CHECK(std::isnan(db->channels[0][m]));  // never a silent zero
                CHECK(db->valid[m] == 0);
            }
        }
    }
    CHECK(some_length_differs);  // the jittered margins did change
}

TEST_CASE("playback follows the virtual clock through a session", "[replay][session][timing]") {
    rt::TempDir dir;
    // A hand-made dataset recorded at 62.2 Hz, ch1 = sample index.
    std::string trial = "time,ch1,ch2,ch3\n";
    for (int i = 0; i < 200; ++i)
        trial += std::to_string(i / 62.2) + "," + std::to_string(i) + ",0,0\n";
    rt::write_file(dir / "ds/manifest.csv", "trial_id,file,object,speed,repetition,samples\nfast,trials/fast.csv,C1,10,1,200\n");
    rt::write_file(dir / "ds/trials/fast.csv", trial);
    // Record 1.5 s after moving nothing: a script that only waits.
    rt::write_file(dir / "wait.lua", R"(
local rs = require "rollsense"
rs.wait(1234)  -- the recording starts anywhere in the run
rs.trial{ object = "C1", speed = 10, repetition = 1 }
rs.record_start()
rs.wait(1500)
rs.record_stop()
rs.save_trial()
rs.end_trial()
)");
    auto summary = run(session_options(dir / "wait.lua", "replay", dir / "out", 1, {"dataset=" + (dir / "ds").string()}));
    INFO(summary.status.message());
    REQUIRE(summary.status.ok());
    auto out = open_dataset(dir / "out");
    auto d = out.load(out.trials().front());
    REQUIRE(d.ok());
    // 1.5 s at 31.1 Hz: samples at 0, 1/31.1, ... 1.5 s → 47 samples (the last at 1.479 s).
    REQUIRE(d->samples() == 47);
    for (std::size_t m = 0; m < d->samples(); ++m) {
        INFO("sample " << m);
        CHECK(d->time[m] == Approx(static_cast<double>(m) / 31.1).margin(1e-6));
        CHECK(d->channels[0][m] == static_cast<double>(2 * m));  // 62.2 Hz recording, every other sample
        CHECK(d->valid[m] == 1);
    }
}

TEST_CASE("a bad trial file stops the replay with its place, and the trials before it are kept",
          "[replay][session][malformed]") {
    rt::TempDir dir;
    const std::vector<std::string> two = {"runs=2", "objects=C1", "speeds=10", "analyse=false"};
    REQUIRE(run(session_options(kPaperScript, "mock", dir / "recorded", 5, two)).status.ok());
    // Break the second trial's third row.
    const fs::path bad = dir / "recorded/trials/C1-v10-r002.csv";
    std::string text = rt::read_file(bad);
    auto line3 = text.find('\n', text.find('\n') + 1) + 1;
    text.replace(line3, text.find(',', line3) - line3, "0.06x");
    rt::write_file(bad, text);

    auto replayed = run(session_options(kPaperScript, "replay", dir / "replayed", 5,
                                        with(two, "dataset=" + (dir / "recorded").string())));
    REQUIRE_FALSE(replayed.status.ok());
    INFO(replayed.status.message());
    CHECK(replayed.status.message().find(bad.string() + ":3: column 'time': '0.06x' is not a number") !=
          std::string::npos);
    CHECK(replayed.status.message().find("tactile") != std::string::npos);  // names the device
    CHECK(replayed.trials_saved == 1);
    auto out = open_dataset(dir / "replayed");
    REQUIRE(out.trials().size() == 1);
    CHECK(out.trials()[0].info.id == "C1-v10-r001");
}
