// The nearest-centroid model loader (plugins/classifiers/nearest_centroid/
// src/model_file.cpp), as is and with a correct checksum line appended.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "rollsense/nearest_centroid/nearest_centroid.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using rollsense::nearest_centroid::Model;
    const std::string text(reinterpret_cast<const char*>(data), size);
    {
        Model m;
        (void)m.deserialize(text, "fuzz.rsm");
    }
    Model m;
    if (m.deserialize(text + rollsense::fuzz::checksum_line(text), "fuzz.rsm").ok() &&
        m.centroids.size() != m.class_names.size() * m.feature_names.size())
        rollsense::fuzz::invariant_broken("centroid table does not match K x P");
    return 0;
}
