// The bagged-trees model loader (plugins/classifiers/bagged_trees/src/
// model_file.cpp). Each input is tried as it is, and with a correct checksum
// line appended so mutations reach the structure checks; a model that loads
// must serialize back to the bytes it was read from.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "rollsense/bagged_trees/ensemble.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using rollsense::bagged_trees::Ensemble;
    const std::string text(reinterpret_cast<const char*>(data), size);
    {
        Ensemble e;
        (void)e.deserialize(text, "fuzz.rsm");
    }
    const std::string sealed = text + rollsense::fuzz::checksum_line(text);
    Ensemble e;
    if (e.deserialize(sealed, "fuzz.rsm").ok() && !e.trained())
        rollsense::fuzz::invariant_broken("a loaded bagged-trees model is not trained");
    return 0;
}
