// The MiniRocket model loader (plugins/classifiers/minirocket/src/
// model_file.cpp), as is and with a correct checksum line appended.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "rollsense/minirocket/minirocket.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace rollsense::minirocket;
    const std::string text(reinterpret_cast<const char*>(data), size);
    {
        Model m;
        Options o;
        (void)m.deserialize(text, "fuzz.rsm", o);
    }
    Model m;
    Options o;
    if (m.deserialize(text + rollsense::fuzz::checksum_line(text), "fuzz.rsm", o).ok() &&
        m.weights.size() != m.transform.features() * m.class_names.size())
        rollsense::fuzz::invariant_broken("weight table does not match P x K");
    return 0;
}
