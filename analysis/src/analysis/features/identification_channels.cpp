// Which three sensor channels of a dataset the identification reads. Named,
// never guessed: a dataset of one three-channel sensor needs no name; with
// more channels the profile's `identification_channels` (recorded into
// dataset-info.csv) says which three, and without it the analysis stops
// with the channels it could choose from.
#include <algorithm>

#include "rollsense/features.hpp"

namespace rollsense::features {

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? "none" : out;
}

}  // namespace

Result<std::array<std::size_t, kChannels>> identification_channels(const DatasetInfo& info,
                                                                   const std::string& dataset) {
    const auto& all = info.channels;
    // A recording still in memory (no folder) has no dataset-info.csv to edit yet (review: its way out named one).
    const std::string what = dataset.empty() ? "the recording" : "dataset " + dataset;
    std::array<std::size_t, kChannels> out{};
    if (info.identification_channels.empty()) {
        if (all.size() == kChannels) {
            for (std::size_t c = 0; c < kChannels; ++c) out[c] = c;
            return out;
        }
        const std::string way_out =
            "name the three the identification reads: identification_channels = {\"a\", \"b\", \"c\"} in the "
            "robot profile (recorded into dataset-info.csv)" +
            (dataset.empty() ? std::string() : ", or an identification_channels row in " + dataset +
                                                   "/dataset-info.csv (space-separated column names)");
        if (all.size() < kChannels)
            return Error{ErrorCode::invalid_argument, what + " has " + std::to_string(all.size()) +
                                                          " sensor channels (" + joined(all) +
                                                          "); the identification needs 3"};
        return Error{ErrorCode::invalid_argument, what + " has " + std::to_string(all.size()) +
                                                      " sensor channels (" + joined(all) +
                                                      ") and does not say which three identify the object; " + way_out};
    }
    if (info.identification_channels.size() != kChannels)
        return Error{ErrorCode::invalid_argument,
                     what + ": identification_channels names " +
                         std::to_string(info.identification_channels.size()) + " channels (" +
                         joined(info.identification_channels) + "); the identification needs exactly 3, in the "
                         "order the object crosses them"};
    for (std::size_t c = 0; c < kChannels; ++c) {
        const auto& name = info.identification_channels[c];
        const auto it = std::find(all.begin(), all.end(), name);
        if (it == all.end())
            return Error{ErrorCode::invalid_argument, what + ": identification_channels names '" +
                                                          name + "', which is not one of its sensor channels (" +
                                                          joined(all) + ")"};
        out[c] = static_cast<std::size_t>(it - all.begin());
    }
    return out;
}

}  // namespace rollsense::features
