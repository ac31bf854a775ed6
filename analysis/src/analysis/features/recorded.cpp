#include "rollsense/features/recorded.hpp"

#include <cmath>

namespace rollsense::features {

void RecordedFeatures::add(const DatasetInfo& info, const TrialRecord& record, const TrialData& data) {
    auto columns = identification_channels(info, std::string());
    if (!columns) return;
    // The reader refuses a file whose time is not finite and increasing: such a
    // trial is left to the file, where it gets the reader's reason.
    for (std::size_t i = 0; i < data.time.size(); ++i)
        if (!std::isfinite(data.time[i]) || (i > 0 && data.time[i] <= data.time[i - 1])) return;
    const IdentificationInput in = identification_input(data, *columns);
    std::lock_guard lock(mutex_);
    auto tf = extractor_.extract(std::span<const std::span<const double>>(in.channels), in.time);
    if (!tf) return;
    FeatureRow row;  // the extraction's part; the identity comes from the manifest
    row.clean = tf->clean;
    row.reason = tf->reason;
    row.values = tf->values;
    for (std::size_t c = 0; c < kChannels; ++c) row.windows[c] = tf->channels[c].window;
    rows_.insert_or_assign(record.info.id, std::move(row));
}

std::size_t RecordedFeatures::size() const {
    std::lock_guard lock(mutex_);
    return rows_.size();
}

Result<std::vector<FeatureRow>> RecordedFeatures::extract(const DatasetReader& dataset, unsigned threads,
                                                          const std::atomic<bool>* stop) const {
    std::lock_guard lock(mutex_);
    return extract_dataset(dataset, extractor_.settings(), threads, stop, &rows_);
}

}  // namespace rollsense::features
