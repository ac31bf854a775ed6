// The features file (analysis/src/analysis/features/feature_file.cpp):
// read_features_csv, then the table built from it.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.hpp"
#include "rollsense/features.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = rollsense::fuzz::scratch_dir() / "features.csv";
    rollsense::fuzz::write_file(file, std::string_view(reinterpret_cast<const char*>(data), size));
    auto rows = rollsense::features::read_features_csv(file);
    if (!rows.ok()) return 0;
    auto table = rollsense::features::to_feature_table(*rows, nullptr);
    if (table.x.size() != table.rows * table.feature_names.size() || table.y.size() != table.rows)
        rollsense::fuzz::invariant_broken("feature table shape");
    return 0;
}
