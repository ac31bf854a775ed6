#include "analysis/series/series_table.hpp"

#include <algorithm>
#include <atomic>
#include <map>
#include <optional>
#include <thread>

#include "analysis/series/model_rule.hpp"

namespace rollsense::series {

Result<std::vector<std::size_t>> channel_indices(const DatasetInfo& info, const std::vector<std::string>& names) {
    if (names.empty())
        return Error{ErrorCode::invalid_argument, "series table: no channel named; pass e.g. ch1 ch2 ch3"};
    std::vector<std::size_t> idx;
    for (const auto& name : names) {
        const auto it = std::find(info.channels.begin(), info.channels.end(), name);
        if (it == info.channels.end()) {
            std::string have;
            for (const auto& c : info.channels) have += (have.empty() ? "" : " ") + c;
            return Error{ErrorCode::not_found,
                         "series table: the dataset records no channel '" + name + "' (it has: " + have + ")"};
        }
        idx.push_back(static_cast<std::size_t>(it - info.channels.begin()));
    }
    return idx;
}

Result<SeriesTable> series_table(const DatasetReader& dataset, std::span<const TrialRecord> trials,
                                 const std::vector<std::string>& channel_names, const SeriesSettings& settings,
                                 unsigned threads) {
    if (auto st = validate(settings); !st) return st.error();
    auto idx = channel_indices(dataset.info(), channel_names);
    if (!idx) return idx.error();

    // Each trial is independent: workers take the next index, and results land
    // in their trial's slot, so the order (and the table) never depends on timing.
    std::vector<std::optional<Result<PreparedSeries>>> done(trials.size());
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i; (i = next.fetch_add(1)) < trials.size();) {
            auto data = dataset.load(trials[i]);
            if (!data) {
                done[i].emplace(Error{data.error().code, "series table: trial " + trials[i].info.id + " (" +
                                                             (dataset.dir() / trials[i].file).string() +
                                                             "): " + data.error().message});
                continue;
            }
            done[i].emplace(prepare_series(*data, *idx, settings));
        }
    };
    unsigned n = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
    n = static_cast<unsigned>(std::min<std::size_t>(n, std::max<std::size_t>(trials.size(), 1)));
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < n; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();

    SeriesTable out;
    FeatureTable& table = out.table;
    table.channel_names = channel_names;
    describe_series(table, settings);
    std::map<std::string, int> classes;
    for (std::size_t i = 0; i < trials.size(); ++i) {
        if (!done[i]->ok()) return done[i]->error();
        if ((*done[i])->ok) classes.emplace(trials[i].info.object, 0);
    }
    for (auto& [name, label] : classes) {
        label = static_cast<int>(table.class_names.size());
        table.class_names.push_back(name);
    }
    for (std::size_t i = 0; i < trials.size(); ++i) {
        PreparedSeries& p = **done[i];
        if (!p.ok) {
            out.refused.push_back({trials[i].info.id, trials[i].info.object, p.reason});
            continue;
        }
        table.x.insert(table.x.end(), p.values.begin(), p.values.end());
        table.y.push_back(classes[trials[i].info.object]);
        out.trial_ids.push_back(trials[i].info.id);
        ++table.rows;
    }
    return out;
}

}  // namespace rollsense::series
