#include "cli/output_paths.hpp"

#include <cstdio>

#include "cli/command.hpp"
#include "rollsense/atomic_file.hpp"
#include "rollsense/dataset_files.hpp"

namespace rollsense::cli {

int check_output_files(const char* command, const std::filesystem::path& input,
                       const std::vector<std::filesystem::path>& outputs) {
    std::error_code ec;
    const bool dataset = std::filesystem::is_directory(input, ec);
    for (const auto& file : outputs) {
        // The input's files, and any other dataset's the output lands in (review: -o OTHER/manifest.csv replaced
        // another dataset's manifest with a features table).
        std::vector<std::filesystem::path> datasets;
        if (dataset) datasets.push_back(input);
        const auto folder = std::filesystem::absolute(file, ec).parent_path();
        for (const auto& dir : {folder, folder.parent_path()})  // beside the file, or the file under its trials/
            if (holds_dataset(dir)) datasets.push_back(dir);
        for (const auto& dir : datasets)
            if (auto st = check_not_dataset_file(file, dir, "-o"); !st) {
                std::fprintf(stderr, "rollsense %s: %s\n", command, st.message().c_str());
                return kExitUsage;
            }
        if (auto st = check_can_write(file); !st) {
            std::fprintf(stderr, "rollsense %s: %s\n", command, st.message().c_str());
            return exit_code_for(st.code());
        }
    }
    return kExitOk;
}

}  // namespace rollsense::cli
