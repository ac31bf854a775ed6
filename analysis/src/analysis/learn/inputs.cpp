#include "analysis/learn/inputs.hpp"

#include <charconv>
#include <map>

namespace rollsense::learn {
namespace {
// Training and evaluation need every trial's class label; a dataset may hold unlabelled trials for predict (review:
// an empty label became a class of its own).
// `one_row_per_line`: the rows are the file's lines after its header, in order (a features CSV), so the error can
// name the line (review: it named the file only).
Result<std::vector<features::FeatureRow>> labelled(Result<std::vector<features::FeatureRow>> rows,
                                                   const std::filesystem::path& file, bool one_row_per_line) {
    if (rows)
        for (std::size_t i = 0; i < rows->size(); ++i)
            if (const auto& r = (*rows)[i]; r.object.empty())
                return Error{ErrorCode::parse_error, file.string() + (one_row_per_line ? ":" + std::to_string(i + 2) : "") +
                                                     ": trial '" + r.trial_id + "' has no object "
                                                     "(class label): label it to train or evaluate on it (predict "
                                                     "needs none), or leave it out"};
    return rows;
}
}  // namespace

Result<std::vector<features::FeatureRow>> load_feature_rows(const std::filesystem::path& input,
                                                            const features::FeatureSettings& settings,
                                                            unsigned threads, const std::atomic<bool>* stop,
                                                            const features::RecordedFeatures* recorded) {
    std::error_code ec;
    if (std::filesystem::is_directory(input, ec)) {
        auto ds = DatasetReader::open(input);
        if (!ds) return ds.error();
        return labelled(recorded ? recorded->extract(*ds, threads, stop)
                                 : features::extract_dataset(*ds, settings, threads, stop),
                        input / "manifest.csv", false);
    }
    if (!std::filesystem::exists(input, ec))
        return Error{ErrorCode::not_found, "'" + input.string() +
                                               "' does not exist (expected a dataset folder or a features CSV)"};
    return labelled(features::read_features_csv(input), input, true);
}

Status parse_assignment(const std::string& text, ParamSet& into) {
    const auto eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        return {ErrorCode::invalid_argument, "'" + text + "' is not key=value (e.g. learners=100)"};
    const std::string key = text.substr(0, eq), value = text.substr(eq + 1);
    const char* b = value.data();
    const char* e = value.data() + value.size();
    std::int64_t i = 0;
    if (auto [p, ec] = std::from_chars(b, e, i); ec == std::errc() && p == e && !value.empty()) {
        into.set(key, i);
        return {};
    }
    double d = 0;
    if (auto [p, ec] = std::from_chars(b, e, d); ec == std::errc() && p == e && !value.empty()) {
        into.set(key, d);
        return {};
    }
    if (value == "true" || value == "false") {
        into.set(key, value == "true");
        return {};
    }
    into.set(key, value);
    return {};
}

std::string summarize_rejections(const std::vector<features::FeatureRow>& rows) {
    std::map<std::string, std::size_t> reasons;
    std::size_t clean = 0;
    for (const auto& r : rows) {
        if (r.clean) {
            ++clean;
            continue;
        }
        // Count by channel and reason code, without the numbers in brackets.
        std::size_t start = 0;
        while (start < r.reason.size()) {
            auto end = r.reason.find("; ", start);
            if (end == std::string::npos) end = r.reason.size();
            std::string clause = r.reason.substr(start, end - start);
            if (auto paren = clause.find(" ("); paren != std::string::npos) clause.resize(paren);
            ++reasons[clause];
            start = end + 2;
        }
    }
    std::string out = "clean " + std::to_string(clean) + " of " + std::to_string(rows.size());
    if (!reasons.empty()) {
        out += "; rejected trials by reason:";
        for (const auto& [why, n] : reasons) out += " " + why + " " + std::to_string(n) + ",";
        out.pop_back();
    }
    return out;
}

}  // namespace rollsense::learn
