// Features from memory (issue 25): the features of the trials a run records,
// taken as each trial becomes durable while it is still in memory (the dataset
// writer's on_durable observer gives it as its file holds it), so that the
// run's own analysis does not read its trial files back. The rows are those
// extract_dataset() would compute from the files, bit for bit.
#pragma once

#include <atomic>
#include <mutex>

#include "rollsense/dataset.hpp"
#include "rollsense/features.hpp"

namespace rollsense::features {

class RecordedFeatures {
public:
    explicit RecordedFeatures(FeatureSettings settings = {}) : extractor_(std::move(settings)) {}
    const FeatureSettings& settings() const { return extractor_.settings(); }

    // One durable trial (DatasetWriter::DurableObserver), on the writer's
    // thread. A trial the extractor cannot take (no identification channels,
    // a structural error) is left to be read from its file.
    void add(const DatasetInfo& info, const TrialRecord& record, const TrialData& data);
    std::size_t size() const;

    // extract_dataset() of `dataset` with these settings, reading from their
    // files only the trials not taken here (a resumed run's earlier trials).
    Result<std::vector<FeatureRow>> extract(const DatasetReader& dataset, unsigned threads = 0,
                                            const std::atomic<bool>* stop = nullptr) const;

private:
    mutable std::mutex mutex_;
    FeatureExtractor extractor_;  // used on the writer's thread only, under mutex_
    KnownRows rows_;
};

}  // namespace rollsense::features
