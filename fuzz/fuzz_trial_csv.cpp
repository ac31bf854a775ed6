// One trial file (data/src/dataset.cpp, DatasetReader::load) of a dataset
// with channels ch1..ch3 and one joint. The first input byte picks the row
// count the manifest claims (0 = unknown), the rest is the trial's CSV.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "rollsense/dataset.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace fs = std::filesystem;
    if (size == 0) return 0;
    static const fs::path dir = [] {
        const fs::path d = rollsense::fuzz::scratch_dir() / "trial";
        fs::create_directories(d / "trials");
        rollsense::fuzz::write_file(d / "dataset-info.csv",
                                    "key,value\nformat,rollsense-dataset\nformat_version,1\nsample_rate_hz,31.1\n"
                                    "channels,ch1 ch2 ch3\njoints,sensing_finger\nprofile,sim\nseed,1\n");
        return d;
    }();
    // The claimed count: small ones match real inputs, 255 stands for "huge".
    const std::uint64_t claimed = data[0] == 255 ? 999'999'999 : data[0];
    rollsense::fuzz::write_file(dir / "manifest.csv",
                                "trial_id,file,object,speed,repetition,seed,samples,invalid_samples,extra\n"
                                "t1,trials/t1.csv,C1,10,1,5," + std::to_string(claimed) + ",0,\n");
    rollsense::fuzz::write_file(dir / "trials" / "t1.csv",
                                std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
    auto reader = rollsense::DatasetReader::open(dir);
    if (!reader.ok()) return 0;
    auto trial = reader->load(reader->trials().front());
    if (trial.ok()) {
        const auto& t = *trial;
        if (t.channels.size() != 3 || t.joints.size() != 1 || t.valid.size() != t.samples())
            rollsense::fuzz::invariant_broken("trial columns do not match the dataset");
        for (const auto& c : t.channels)
            if (c.size() != t.samples()) rollsense::fuzz::invariant_broken("ragged channel");
    }
    return 0;
}
