// The series rule a model was trained with travels in its model file
// (analysis/series/model_rule.hpp): its text round-trips every setting, a bad
// one is refused naming the file and the key, and `rollsense predict` prepares
// a dataset for a z_per_channel model exactly as training did — the defect
// this fixes: predict used to prepare with the default amplitude.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "analysis/series/model_rule.hpp"
#include "analysis/series/series_table.hpp"
#include "cli_dataset.hpp"
#include "json_reader.hpp"
#include "rollsense/minirocket/minirocket.hpp"
#include "rollsense/model_text.hpp"
#include "run_command.hpp"

using namespace rollsense;
using namespace rollsense::series;
namespace fs = std::filesystem;

TEST_CASE("the rule text gives back every setting that shapes the row", "[series][model_rule]") {
    SeriesSettings s;
    s.length = 64;
    s.detect_window = 7;
    s.contact_fraction = 0.15;
    s.noise_floor = 0.02;
    s.min_amplitude = 0.05;
    s.margin = 0.2;
    s.require_complete_contact = false;
    s.amplitude = Amplitude::z_per_channel;
    s.scale = 0.1 + 0.2;  // not a short decimal: must still read back exactly
    s.z_floor = 0.003;
    s.max_invalid_fraction = 0.25;
    s.max_gap = 9;
    s.time_axis = TimeAxis::roll_relative;
    s.prefix = 40;      // how much of a recording is used, not how it is prepared:
    s.open_end = true;  // neither is recorded
    const std::string text = rule_text(s);
    CHECK(text.find('\n') == std::string::npos);
    CHECK(text.find("prefix") == std::string::npos);
    CHECK(text.find("open_end") == std::string::npos);
    auto back = parse_rule_text(text, "m.rsm");
    REQUIRE(back.ok());
    s.prefix = 0;
    s.open_end = false;
    CHECK(rule_text(*back) == text);
    CHECK(back->length == 64);
    CHECK(back->detect_window == 7);
    CHECK(back->contact_fraction == 0.15);
    CHECK(back->noise_floor == 0.02);
    CHECK(back->min_amplitude == 0.05);
    CHECK(back->margin == 0.2);
    CHECK(!back->require_complete_contact);
    CHECK(back->amplitude == Amplitude::z_per_channel);
    CHECK(back->scale == 0.1 + 0.2);
    CHECK(back->z_floor == 0.003);
    CHECK(back->max_invalid_fraction == 0.25);
    CHECK(back->max_gap == 9);
    CHECK(back->time_axis == TimeAxis::roll_relative);
    CHECK(back->prefix == 0);
    CHECK(!back->open_end);
    // The defaults' text, as docs/series-preparation.md shows it.
    CHECK(rule_text({}) == "length=128 detect_window=5 contact_fraction=0.1 noise_floor=0.01 min_amplitude=0.03 "
                           "margin=0.1 require_complete_contact=true amplitude=global_scale scale=1 z_floor=0.01 "
                           "max_invalid_fraction=0.1 max_gap=5 time_axis=contact");
    // A key left out keeps its default.
    auto some = parse_rule_text("amplitude=z_per_channel", "m.rsm");
    REQUIRE(some.ok());
    CHECK(some->amplitude == Amplitude::z_per_channel);
    CHECK(some->length == 128);
}

TEST_CASE("a malformed rule is refused naming the model file and the key", "[series][model_rule][errors]") {
    auto refused = [](const std::string& text, const std::string& reason) {
        auto r = parse_rule_text(text, "runs/a/m.rsm");
        REQUIRE(!r.ok());
        INFO(r.error().message);
        CHECK(r.error().code == ErrorCode::parse_error);
        CHECK_THAT(r.error().message, Catch::Contains("model file 'runs/a/m.rsm': series_rule: ") &&
                                          Catch::Contains(reason) && Catch::Contains("train the model again"));
    };
    refused("length=128 loudness=3", "unknown setting 'loudness'");
    refused("amplitude=loud", "setting 'amplitude' has a malformed value 'loud'");
    refused("length=12x", "setting 'length' has a malformed value '12x'");
    refused("length=-4", "setting 'length' has a malformed value '-4'");
    refused("scale=nan", "setting 'scale' has a malformed value 'nan'");
    refused("require_complete_contact=yes", "'require_complete_contact' has a malformed value 'yes'");
    refused("length=64 length=128", "setting 'length' given twice");
    refused("length", "'length' is not key=value");
    refused("length=1", "length 1 must be at least 2");  // validate(): out of range
}

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// The JSON array of `predict --json` in its output (the notes on stderr come first).
std::string json_of(const std::string& output) {
    const auto at = output.rfind("\n[\n");
    return output.substr(output.rfind("[\n", 0) == 0 || at == std::string::npos ? 0 : at + 1);
}

// Trial id → class, as the model predicts each row of `table`.
std::map<std::string, std::string> predictions(const minirocket::MiniRocket& model, const SeriesTable& table) {
    std::map<std::string, std::string> out;
    for (std::size_t r = 0; r < table.trial_ids.size(); ++r) {
        auto p = model.predict(table.table.row(r));
        REQUIRE(p.ok());
        out[table.trial_ids[r]] = p->class_name;
    }
    return out;
}

}  // namespace

TEST_CASE("rollsense predict prepares a z_per_channel model's trials as training did", "[series][model_rule][cli]") {
    const auto root = rollsense::testing::make_dataset();
    const auto dataset = root / "dataset";
    const auto model = root / "z.rsm";
    auto r = rollsense::testing::run_rollsense("train " + dataset.string() + " -o " + model.string() +
                                               " --classifier minirocket:num_features=168 --series-amplitude "
                                               "z_per_channel -q");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(slurp(model), Catch::Contains("\nseries_rule length=128 ") && Catch::Contains(" amplitude=z_per_channel "));

    // What the model predicts for every trial prepared with the right
    // settings, and with the default amplitude (which must differ somewhere,
    // or this test could not tell the two apart).
    minirocket::MiniRocket loaded;
    REQUIRE(loaded.load(model).ok());
    auto reader = DatasetReader::open(dataset);
    REQUIRE(reader.ok());
    const std::vector<std::string> channels{"ch1", "ch2", "ch3"};
    SeriesSettings z;
    z.amplitude = Amplitude::z_per_channel;
    auto right_table = series_table(*reader, reader->trials(), channels, z, 1);
    auto default_table = series_table(*reader, reader->trials(), channels, {}, 1);
    REQUIRE(right_table.ok());
    REQUIRE(default_table.ok());
    const auto right = predictions(loaded, *right_table), wrong = predictions(loaded, *default_table);
    REQUIRE(right.size() >= 30);
    int differ = 0;
    for (const auto& [id, cls] : right) differ += wrong.at(id) != cls;
    CHECK(differ > 0);

    r = rollsense::testing::run_rollsense("predict " + model.string() + " " + dataset.string() + " --json");
    INFO(r.output);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, !Catch::Contains("records no series rule"));
    const auto json = rollsense::testing::JsonReader::parse(json_of(r.output));
    std::size_t decided = 0;
    for (const auto& o : json.arr()) {
        const auto& id = o["trial_id"].str();
        if (!right.count(id)) {
            CHECK(o["class"].is_null());  // refused by the series rule
            continue;
        }
        ++decided;
        REQUIRE(!o["class"].is_null());
        CHECK(o["class"].str() == right.at(id));
    }
    CHECK(decided == right.size());

    // The same model in the format before the rule was recorded (version 1, no
    // series_rule line) still loads: prepared by the default rule, as then, and said once.
    const std::string saved = slurp(model);
    std::string v1 = saved.substr(0, saved.rfind("checksum "));
    v1.replace(0, v1.find('\n'), "rollsense-minirocket 1");
    const auto at = v1.find("series_rule ");
    v1.erase(at, v1.find('\n', at) + 1 - at);
    model_text::put_checksum(v1);
    std::ofstream(root / "v1.rsm", std::ios::binary) << v1;
    r = rollsense::testing::run_rollsense("predict " + (root / "v1.rsm").string() + " " + dataset.string() + " --json");
    REQUIRE(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("records no series rule"));
    CHECK(r.output.find("records no series rule") == r.output.rfind("records no series rule"));  // once
    const auto old_json = rollsense::testing::JsonReader::parse(json_of(r.output));
    for (const auto& o : old_json.arr())
        if (wrong.count(o["trial_id"].str())) CHECK(o["class"].str() == wrong.at(o["trial_id"].str()));

    // A malformed rule line is refused before anything is predicted, naming the file and the key.
    std::string text = saved.substr(0, saved.rfind("checksum "));
    text.replace(text.find("amplitude=z_per_channel"), 23, "amplitude=loud");
    model_text::put_checksum(text);
    std::ofstream(root / "bad.rsm", std::ios::binary) << text;
    r = rollsense::testing::run_rollsense("predict " + (root / "bad.rsm").string() + " " + dataset.string());
    CHECK(r.status == 3);  // a bad model file, as any other (kExitConfig)
    CHECK_THAT(r.output, Catch::Contains("model file '" + (root / "bad.rsm").string() +
                                         "': series_rule: setting 'amplitude' has a malformed value 'loud'"));
    // rs.classifier refuses it when it loads the model, naming the file and the key.
    std::ofstream(root / "load.lua") << "local rs = require 'rollsense'\n"
                                        "rs.settings{ model = { kind = 'string', help = 'the model file' } }\n"
                                        "local ok, err = pcall(rs.classifier, { model = rs.setting('model'), classifier = 'minirocket' })\n"
                                        "assert(not ok, 'a malformed series rule was loaded')\n"
                                        "rs.log('refused: ' .. tostring(err))\n";
    r = rollsense::testing::run_rollsense("run " + (root / "load.lua").string() + " --profile sim --out " +
                                          (root / "run").string() + " --set model=" + (root / "bad.rsm").string());
    INFO(r.output);
    CHECK(r.status == 0);
    CHECK_THAT(r.output, Catch::Contains("refused: ") &&
                             Catch::Contains("series_rule: setting 'amplitude' has a malformed value 'loud'"));

    // A rule whose length contradicts the file's series_length is refused too.
    std::string edited = saved.substr(0, saved.rfind("checksum "));
    edited.replace(edited.find("series_rule length=128"), 22, "series_rule length=64");
    model_text::put_checksum(edited);
    std::ofstream(root / "edited.rsm", std::ios::binary) << edited;
    r = rollsense::testing::run_rollsense("predict " + (root / "edited.rsm").string() + " " + dataset.string());
    CHECK(r.status == 3);
    CHECK_THAT(r.output, Catch::Contains("series_rule length=64 but series_length 128"));
    fs::remove_all(root);
}
