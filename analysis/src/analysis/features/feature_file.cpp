// Features of a whole dataset, and the features CSV that MATLAB's
// Classification Learner and pandas read directly.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string_view>
#include <thread>

#include "rollsense/atomic_file.hpp"
#include "rollsense/csv.hpp"
#include "rollsense/features.hpp"

namespace rollsense::features {

IdentificationInput identification_input(const TrialData& data, const std::array<std::size_t, kChannels>& columns) {
    // A sample without a valid flag (a series assembled by hand) counts as valid.
    auto valid = [&data](std::size_t i) { return i >= data.valid.size() || data.valid[i] != 0; };
    std::size_t first = 0, last = data.samples();
    while (first < last && !valid(first)) ++first;
    while (last > first && !valid(last - 1)) --last;
    IdentificationInput in;
    in.first = first;
    for (std::size_t c = 0; c < kChannels; ++c)
        in.channels[c] = std::span<const double>(data.channels[columns[c]]).subspan(first, last - first);
    in.time = std::span<const double>(data.time).subspan(first, last - first);
    return in;
}

Result<std::vector<FeatureRow>> extract_dataset(const DatasetReader& dataset, const FeatureSettings& settings,
                                                unsigned threads, const std::atomic<bool>* stop,
                                                const KnownRows* known) {
    const auto& trials = dataset.trials();
    auto columns = identification_channels(dataset.info(), dataset.dir().string());
    if (!columns) return columns.error();
    std::vector<FeatureRow> rows(trials.size());
    std::atomic<std::size_t> next{0};
    std::atomic<bool> stopped{false};

    auto work = [&] {
        FeatureExtractor extractor(settings);
        for (;;) {
            if (stop && stop->load()) {
                stopped = true;
                return;
            }
            const std::size_t i = next.fetch_add(1);
            if (i >= trials.size()) return;
            const auto& rec = trials[i];
            FeatureRow& row = rows[i];
            row.trial_id = rec.info.id;
            row.object = rec.info.object;
            row.speed = rec.info.speed;
            row.repetition = rec.info.repetition;
            row.extra = rec.info.extra;
            if (known)
                if (const auto it = known->find(rec.info.id); it != known->end()) {
                    row.clean = it->second.clean;
                    row.reason = it->second.reason;
                    row.values = it->second.values;
                    row.windows = it->second.windows;
                    continue;
                }
            // A trial that cannot be read is skipped with the reason; the others go on.
            auto data = dataset.load(rec);
            if (!data) {
                row.reason = "unreadable (" + data.error().message + ")";
                continue;
            }
            const IdentificationInput in = identification_input(*data, *columns);
            auto tf = extractor.extract(std::span<const std::span<const double>>(in.channels), in.time);
            if (!tf) {
                row.reason = "unreadable (" + dataset.dir().string() + "/" + rec.file + ": " + tf.error().message + ")";
                continue;
            }
            row.clean = tf->clean;
            row.reason = tf->reason;
            row.values = tf->values;
            for (std::size_t c = 0; c < kChannels; ++c) row.windows[c] = tf->channels[c].window;
        }
    };
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(trials.size(), 1)));
    if (threads <= 1) {
        work();
    } else {
        std::vector<std::thread> pool;
        for (unsigned t = 0; t < threads; ++t) pool.emplace_back(work);
        for (auto& t : pool) t.join();
    }
    if (stopped) return Error{ErrorCode::cancelled, "feature extraction interrupted"};
    return rows;
}

namespace {

// The keys of every trial's extra metadata, sorted: the extra_<key> columns.
std::vector<std::string> extra_keys(const std::vector<FeatureRow>& rows) {
    std::set<std::string> keys;
    for (const auto& r : rows)
        for (const auto& [k, v] : r.extra) keys.insert(k);
    return {keys.begin(), keys.end()};
}

constexpr std::string_view kExtraPrefix = "extra_";

}  // namespace

std::string format_features_csv(const std::vector<FeatureRow>& rows) {
    std::vector<std::string> header = {"trial_id", "object", "speed", "repetition", "clean", "reason"};
    for (const auto& n : feature_names()) header.push_back(n);
    for (std::size_t c = 0; c < kChannels; ++c) header.push_back("window_ch" + std::to_string(c + 1));
    const auto keys = extra_keys(rows);
    for (const auto& k : keys) header.push_back(std::string(kExtraPrefix) + k);
    std::string out;
    csv::append_row(out, header);
    std::vector<std::string> f;
    for (const auto& r : rows) {
        f.clear();
        f.push_back(r.trial_id);
        f.push_back(r.object);
        f.push_back(r.speed);
        f.push_back(std::to_string(r.repetition));
        f.push_back(r.clean ? "1" : "0");
        f.push_back(r.reason);
        // Rejected trials keep their row but get empty features, which both
        // readtable and read_csv load as NaN: never silently usable.
        for (double v : r.values) f.push_back(r.clean && std::isfinite(v) ? csv::format_number(v) : "");
        for (const auto& w : r.windows) f.push_back(w ? std::to_string(*w) : "");
        for (const auto& k : keys) {
            const auto it = r.extra.find(k);
            f.push_back(it == r.extra.end() ? std::string() : it->second);
        }
        csv::append_row(out, f);
    }
    return out;
}

Status write_features_csv(const std::filesystem::path& file, const std::vector<FeatureRow>& rows) {
    return write_file_atomic(file, format_features_csv(rows));
}

Result<std::vector<FeatureRow>> read_features_csv(const std::filesystem::path& file) {
    auto reader = csv::Reader::open(file);
    if (!reader) return reader.error();
    auto& r = *reader;
    auto required = [&](std::string_view name) { return r.column(name); };
    auto optional = [&](std::string_view name) -> std::size_t {
        auto c = r.column(name);
        return c ? *c : SIZE_MAX;
    };
    auto id_col = required("trial_id");
    if (!id_col) return id_col.error();
    auto obj_col = required("object");
    if (!obj_col) return obj_col.error();
    auto clean_col = required("clean");
    if (!clean_col) return clean_col.error();
    std::array<std::size_t, kFeatureCount> fcol{};
    for (std::size_t k = 0; k < kFeatureCount; ++k) {
        auto c = required(feature_names()[k]);
        if (!c) return c.error();
        fcol[k] = *c;
    }
    const std::size_t speed_col = optional("speed"), rep_col = optional("repetition"), reason_col = optional("reason");
    std::array<std::size_t, kChannels> wcol{};
    for (std::size_t c = 0; c < kChannels; ++c) wcol[c] = optional("window_ch" + std::to_string(c + 1));
    std::vector<std::pair<std::size_t, std::string>> extra_cols;  // column, key
    for (std::size_t c = 0; c < r.header().size(); ++c)
        if (r.header()[c].rfind(kExtraPrefix, 0) == 0) extra_cols.emplace_back(c, r.header()[c].substr(kExtraPrefix.size()));

    std::vector<FeatureRow> rows;
    std::vector<std::string> f;
    std::map<std::string, std::size_t> line_of;  // trial id → its line
    for (;;) {
        auto more = r.next(f);
        if (!more) return more.error();
        if (!*more) break;
        FeatureRow row;
        row.trial_id = f[*id_col];
        // A copy would sit in a training fold and a test fold at once, and raise every accuracy figure.
        if (const auto [at, fresh] = line_of.emplace(row.trial_id, r.line()); !fresh)
            return Error{ErrorCode::parse_error,
                         r.where(*id_col) + ": trial id '" + row.trial_id + "' appears twice (first at line " +
                             std::to_string(at->second) + "); remove the copy, or write the file again with rollsense "
                                                          "features"};
        row.object = f[*obj_col];
        const std::string& cl = f[*clean_col];
        if (cl == "1" || cl == "true" || cl == "TRUE" || cl == "True") row.clean = true;
        else if (cl == "0" || cl == "false" || cl == "FALSE" || cl == "False") row.clean = false;
        else
            return Error{ErrorCode::parse_error,
                         r.where(*clean_col) + ": '" + cl + "' is not a clean flag (expected 1 or 0)"};
        if (speed_col != SIZE_MAX) row.speed = f[speed_col];
        if (reason_col != SIZE_MAX) row.reason = f[reason_col];
        if (rep_col != SIZE_MAX && !f[rep_col].empty()) {
            auto v = r.integer(f, rep_col, 0, INT32_MAX);
            if (!v) return v.error();
            row.repetition = static_cast<int>(*v);
        }
        for (std::size_t k = 0; k < kFeatureCount; ++k) {
            if (f[fcol[k]].empty()) {
                row.values[k] = std::numeric_limits<double>::quiet_NaN();
                continue;
            }
            auto v = r.number(f, fcol[k]);
            if (!v) return v.error();
            row.values[k] = *v;
        }
        if (row.clean && !std::all_of(row.values.begin(), row.values.end(), [](double v) { return std::isfinite(v); }))
            return Error{ErrorCode::parse_error, r.path().string() + ":" + std::to_string(r.line()) +
                                                     ": trial '" + row.trial_id +
                                                     "' is marked clean but has a missing or non-finite feature"};
        for (std::size_t c = 0; c < kChannels; ++c) {
            if (wcol[c] == SIZE_MAX || f[wcol[c]].empty()) continue;
            auto v = r.integer(f, wcol[c], 0, INT32_MAX);
            if (!v) return v.error();
            row.windows[c] = static_cast<int>(*v);
        }
        for (const auto& [c, key] : extra_cols)
            if (!f[c].empty()) row.extra[key] = f[c];
        rows.push_back(std::move(row));
    }
    return rows;
}

FeatureTable to_feature_table(const std::vector<FeatureRow>& rows, std::vector<std::size_t>* row_index) {
    FeatureTable t;
    t.feature_names.assign(feature_names().begin(), feature_names().end());
    std::map<std::string, int> classes;
    for (const auto& r : rows)
        if (r.clean) classes.emplace(r.object, 0);
    int next = 0;
    for (auto& [name, id] : classes) {
        id = next++;
        t.class_names.push_back(name);
    }
    if (row_index) row_index->clear();
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& r = rows[i];
        if (!r.clean) continue;
        t.x.insert(t.x.end(), r.values.begin(), r.values.end());
        t.y.push_back(classes[r.object]);
        if (row_index) row_index->push_back(i);
        ++t.rows;
    }
    return t;
}

}  // namespace rollsense::features
