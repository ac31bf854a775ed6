// rollsense features DATASET -o FILE: the 13 features of every trial, with the
// clean/rejected decision and its reason, as a CSV for MATLAB and pandas.
#include <cstdio>
#include <string>
#include <string_view>
#include <utility>

#include "cli/command.hpp"
#include "cli/log_setup.hpp"
#include "cli/output_paths.hpp"
#include "cli/partial_dataset.hpp"
#include "cli/trial_warnings.hpp"
#include "rollsense/features.hpp"
#include "analysis/learn/inputs.hpp"

namespace rollsense::cli {
namespace {

const char* kHelp = R"(usage: rollsense features DATASET -o FILE [options]

Smooth every trial's three channels (MATLAB smoothdata 'gaussian' with a
smoothing factor), find each channel's peak (walk out from the maximum to 5 %
of it), decide clean or rejected (max > 0.01 and a complete peak on every
channel) and compute the 13 features F1..F13 in the paper's order.

The CSV has one row per trial: trial_id, object, speed, repetition, clean (1/0),
reason, F1..F13 (empty for rejected trials), window_ch1..3 (the smoothing
windows; empty for a trial that could not be read), then one
extra_NAME column per extra manifest column (e.g. extra_mount), in name order.
MATLAB: readtable(FILE); pandas: pd.read_csv(FILE). -o - (or /dev/stdout)
writes the table alone on stdout (the summary goes to stderr).

options (defaults reproduce the paper):
  -o, --output FILE        the features CSV to write (required; - for stdout)
  --smoothing-factor F     MATLAB SmoothingFactor, in [0, 1] (0.05)
  --window W               fixed Gaussian window in samples (a whole number from 1 to 10000)
                           instead of MATLAB's heuristic
  --window-scope S         per_channel (default) or shared (one window from the 3-channel matrix)
  --peak-fraction P        a peak ends below this fraction of its maximum, in (0, 1) (0.05)
  --min-amplitude A        a valid peak's maximum must exceed this, a number >= 0 (0.01)
  --allow-incomplete       accept peaks cut off by the start or end of the recording
  --half-width RULE        outermost (default) or contiguous 50 % crossings
  --time-base B            samples (default) or timestamps
  --interpolate            sub-sample interpolation of the 5 % and 50 % crossings
  -v, --verbose            debug messages;   -q, --quiet   no info messages: warnings, errors
  --threads N              extraction threads, 0 to 4096 (0 = all cores; results do not depend on it))";

double number_option(const Args& args, std::string_view name, double fallback) {
    const std::string v = args.option(name);
    if (v.empty()) return fallback;
    try {
        std::size_t used = 0;
        const double d = std::stod(v, &used);
        if (used != v.size()) throw std::invalid_argument(v);
        return d;
    } catch (const std::exception&) {
        throw UsageError(std::string(name) + " expects a number, got '" + v + "'");
    }
}

// The option that sets each number feature_settings_from checks.
constexpr std::pair<std::string_view, std::string_view> kSettingOptions[] = {
    {"smoothing_factor", "--smoothing-factor"},
    {"smoothing_window", "--window"},
    {"peak_fraction", "--peak-fraction"},
    {"min_amplitude", "--min-amplitude"},
};

}  // namespace

// Shared with evaluate, train, report and predict: the feature settings from the command line.
features::FeatureSettings feature_settings_from_args(const Args& args) {
    features::FeatureSettings s;
    s.smoothing_factor = number_option(args, "--smoothing-factor", s.smoothing_factor);
    // Left out = MATLAB's heuristic (smoothing_window 0), so a given window is at least 1.
    s.smoothing_window = static_cast<int>(args.unsigned_option("--window", 0, 1, features::kMaxSmoothingWindow));
    s.peak_fraction = number_option(args, "--peak-fraction", s.peak_fraction);
    s.min_amplitude = number_option(args, "--min-amplitude", s.min_amplitude);
    s.require_complete_peak = !args.flag("--allow-incomplete");
    s.interpolate_crossings = args.flag("--interpolate");
    if (auto v = args.option("--window-scope"); !v.empty()) {
        if (v != "per_channel" && v != "shared") throw UsageError("--window-scope is per_channel or shared");
        s.window_scope = v == "shared" ? features::WindowScope::shared : features::WindowScope::per_channel;
    }
    if (auto v = args.option("--half-width"); !v.empty()) {
        if (v != "outermost" && v != "contiguous") throw UsageError("--half-width is outermost or contiguous");
        s.half_width = v == "contiguous" ? features::HalfWidthRule::contiguous : features::HalfWidthRule::outermost;
    }
    if (auto v = args.option("--time-base"); !v.empty()) {
        if (v != "samples" && v != "timestamps") throw UsageError("--time-base is samples or timestamps");
        s.time_base = v == "timestamps" ? features::TimeBase::timestamps : features::TimeBase::samples;
    }
    auto checked = features::feature_settings_from(features::to_params(s));
    if (!checked) {
        // The check names the setting first: say the option instead.
        std::string message = checked.error().message;
        for (const auto& [setting, option] : kSettingOptions)
            if (message.rfind(setting, 0) == 0) message = std::string(option) + message.substr(setting.size());
        throw UsageError(message);
    }
    return s;
}

const std::vector<std::string>& feature_option_names() {
    static const std::vector<std::string> names = {"--smoothing-factor", "--window",     "--window-scope",
                                                  "--peak-fraction",    "--min-amplitude", "--half-width",
                                                  "--time-base",        "--threads"};
    return names;
}
const std::vector<std::string>& feature_flag_names() {
    static const std::vector<std::string> names = {"--allow-incomplete", "--interpolate"};
    return names;
}

namespace {

int run(const std::vector<std::string>& argv) {
    Args args(argv);
    std::vector<std::string> known = feature_option_names();
    known.insert(known.end(), feature_flag_names().begin(), feature_flag_names().end());
    for (const char* k : {"-o", "--output", "-v", "--verbose", "-q", "--quiet"}) known.emplace_back(k);
    args.reject_unknown(known);
    setup_logging(args);
    std::vector<std::string> valued = feature_option_names();
    valued.insert(valued.end(), {"-o", "--output"});
    const auto pos = args.positionals(valued);
    if (pos.size() != 1) throw UsageError("expected one DATASET folder (see rollsense features --help)");
    const std::string out = output_option(args);
    if (out.empty()) throw UsageError("-o FILE is required: where to write the features CSV");
    const auto settings = feature_settings_from_args(args);
    const auto threads = static_cast<unsigned>(args.unsigned_option("--threads", 0, 0, 4096));
    if (int rc = check_output_files("features", pos[0], {out}); rc != kExitOk) return rc;

    std::error_code ec;
    if (!std::filesystem::is_directory(pos[0], ec)) {
        std::fprintf(stderr, "rollsense features: '%s' is not a dataset folder (it needs manifest.csv and trials/)\n",
                     pos[0].c_str());
        return kExitConfig;
    }
    warn_if_partial(pos[0]);
    auto ds = DatasetReader::open(pos[0]);
    if (!ds) {
        std::fprintf(stderr, "rollsense features: %s\n", ds.error().describe().c_str());
        return exit_code_for(ds.error().code, kExitConfig);
    }
    auto rows = features::extract_dataset(*ds, settings, threads);
    if (!rows) {
        std::fprintf(stderr, "rollsense features: %s\n", rows.error().describe().c_str());
        return exit_code_for(rows.error().code, kExitConfig);
    }
    if (auto st = warn_unreadable_trials(*rows); !st) {
        std::fprintf(stderr, "rollsense features: %s\n", st.error().describe().c_str());
        return exit_code_for(st.code(), kExitConfig);
    }
    if (auto s = features::write_features_csv(out, *rows); !s) {
        std::fprintf(stderr, "rollsense features: cannot write '%s': %s\n", out.c_str(), s.error().describe().c_str());
        return exit_code_for(s.code());
    }
    // On stderr: stdout may be the table itself (-o /dev/stdout).
    std::fprintf(stderr, "%s\nwrote %s\n", learn::summarize_rejections(*rows).c_str(), out.c_str());
    return kExitOk;
}

const Registration reg{{"features", "extract the 13 features of a dataset into a CSV", kHelp, &run}};

}  // namespace
}  // namespace rollsense::cli
