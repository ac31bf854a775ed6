// The object catalogue (data/src/object_catalogue.cpp): whatever loads must
// lie in the documented ranges the simulation relies on.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.hpp"
#include "rollsense/object_catalogue.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto file = rollsense::fuzz::scratch_dir() / "objects.csv";
    rollsense::fuzz::write_file(file, std::string_view(reinterpret_cast<const char*>(data), size));
    auto cat = rollsense::ObjectCatalogue::load(file);
    if (!cat.ok()) return 0;
    for (const auto& o : cat->objects()) {
        if (rollsense::object_problem(o)) rollsense::fuzz::invariant_broken("a loaded object is out of range");
        const double w = o.flat_width();
        if (!std::isfinite(w) || w <= 0.0) rollsense::fuzz::invariant_broken("flat width not finite and positive");
    }
    return 0;
}
