#include "analysis/report/plotted_trial.hpp"

#include <algorithm>

namespace rollsense::report {

Result<PlottedTrial> load_plotted_trial(const DatasetReader& dataset, const TrialRecord& record,
                                        const features::FeatureSettings& settings) {
    auto columns = features::identification_channels(dataset.info(), dataset.dir().string());
    if (!columns) return columns.error();
    auto data = dataset.load(record);
    if (!data) return data.error();
    // The samples the features were computed on (features::identification_input).
    const features::IdentificationInput in = features::identification_input(*data, *columns);
    features::FeatureExtractor extractor(settings);
    auto f = extractor.extract(std::span<const std::span<const double>>(in.channels), in.time);
    if (!f) return Error{f.error().code, "trial '" + record.info.id + "': " + f.error().message};
    PlottedTrial t;
    t.info = record.info;
    t.features = std::move(f).value();
    t.smoothed = extractor.smoothed();
    t.x.resize(in.time.size());
    for (std::size_t i = 0; i < t.x.size(); ++i)
        t.x[i] = settings.time_base == features::TimeBase::samples ? static_cast<double>(i) : in.time[i];
    t.x_label = settings.time_base == features::TimeBase::samples ? "time (samples)" : "time (s)";
    const auto& units = dataset.info().channel_units;
    const std::string unit = (*columns)[0] < units.size() ? units[(*columns)[0]] : "1";
    t.y_label = unit == "1" ? "smoothed reading (unitless, about 1/16 per kPa)" : "smoothed reading (" + unit + ")";
    return t;
}

std::pair<std::size_t, std::size_t> half_maximum_span(const std::vector<double>& smoothed,
                                                      const features::ChannelPeak& peak) {
    if (smoothed.empty()) return {0, 0};
    const std::size_t first = peak.peak.first, last = std::min(peak.peak.last, smoothed.size() - 1);
    const double half = 0.5 * peak.peak.max;
    std::size_t a = peak.peak.max_index, b = peak.peak.max_index;
    for (std::size_t i = first; i <= last; ++i)
        if (smoothed[i] >= half) {
            a = i;
            break;
        }
    for (std::size_t i = last + 1; i-- > first;)
        if (smoothed[i] >= half) {
            b = i;
            break;
        }
    return {a, b};
}

}  // namespace rollsense::report
