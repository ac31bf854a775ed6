// The profile files' key-site scan (data/src/table_source.cpp): the input is
// the text of a Lua file, scanned as the profile loader scans it, then asked
// where a few keys are written. The scan runs on any file a profile names,
// before Lua has judged it, so it must stay bounded on text Lua would refuse.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "rollsense/table_source.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const rollsense::TableSource source("fuzz.lua", text);
    const rollsense::ParamValue number = 31.1, word = std::string("sensing_finger");
    for (const char* path : {"sample_rate_hz", "devices.hand.params.port", "joints.palm.min", "record_joints.1",
                             "devices.tactile.params.cell_angles.2"}) {
        const std::string site = source.where(path, &number);
        if (!site.empty() && site.rfind("fuzz.lua", 0) != 0) rollsense::fuzz::invariant_broken("a site outside the file");
        (void)source.where(path, &word);
        (void)source.where(path, nullptr);
    }
    const std::map<std::string, rollsense::ParamValue> keys{{"joint", word}, {"cell_angles", number}};
    (void)rollsense::key_named_in(text, keys);
    return 0;
}
