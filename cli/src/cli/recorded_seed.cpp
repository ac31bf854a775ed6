#include "cli/recorded_seed.hpp"

#include "rollsense/dataset.hpp"

namespace rollsense::cli {

std::optional<RecordedSeed> recorded_seed(const runtime::SessionOptions& options) {
    // A copy of the settings: reading the profile here must not count as the
    // run's use of a --set key (the end-of-run warning about unused keys).
    const runtime::Settings settings = options.settings;
    auto profile = runtime::load_profile(options.profile, options.share_dir, settings, options.sandbox);
    if (!profile) return std::nullopt;
    for (const auto& device : profile->devices) {
        const auto param = device.params.find("dataset");
        if (param == device.params.end()) continue;
        const auto* dir = std::get_if<std::string>(&param->second);
        if (!dir || dir->empty()) continue;
        auto dataset = DatasetReader::open(*dir);
        if (!dataset || dataset->info().seed == 0) continue;  // hand-made datasets carry no seed
        return RecordedSeed{dataset->info().seed, *dir};
    }
    return std::nullopt;
}

}  // namespace rollsense::cli
