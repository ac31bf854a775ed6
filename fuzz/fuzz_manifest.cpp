// A dataset's manifest.csv and dataset-info.csv (data/src/dataset.cpp): the
// input up to its first NUL byte is the manifest, the rest (if any) the
// dataset info. Trial files the manifest names are not created, so opening
// fails late for most inputs; both paths are exercised.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.hpp"
#include "rollsense/dataset.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    namespace fs = std::filesystem;
    const std::string_view in(reinterpret_cast<const char*>(data), size);
    const auto nul = in.find('\0');
    const fs::path dir = rollsense::fuzz::scratch_dir() / "manifest";
    fs::create_directories(dir / "trials");
    rollsense::fuzz::write_file(dir / "manifest.csv", in.substr(0, nul));
    std::error_code ec;
    if (nul == std::string_view::npos) fs::remove(dir / "dataset-info.csv", ec);
    else rollsense::fuzz::write_file(dir / "dataset-info.csv", in.substr(nul + 1));
    auto r = rollsense::DatasetReader::open(dir);
    if (r.ok())
        for (const auto& t : r->trials())
            if (t.info.id.empty() || t.file.empty()) rollsense::fuzz::invariant_broken("empty trial id or file");
    return 0;
}
