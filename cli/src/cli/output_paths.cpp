#include "cli/output_paths.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <string_view>

#include "cli/command.hpp"
#include "rollsense/atomic_file.hpp"
#include "rollsense/dataset_files.hpp"

namespace rollsense::cli {
namespace {
// The results a stock run leaves beside its dataset, and the commands that write each (review: `evaluate -o
// RUN/model.rsm` replaced the run's model with an evaluation, and `features -o RUN/report.html` its report).
struct RunResult {
    const char* file;
    const char* what;
    const char* writers[2];
};
constexpr RunResult kRunResults[] = {
    {"features.csv", "the features table", {"features", nullptr}},
    {"evaluation.txt", "the evaluation", {"evaluate", "report"}},
    {"evaluation.json", "the evaluation", {"evaluate", "report"}},
    {"model.rsm", "the trained model", {"train", nullptr}},
    {"report.html", "the report", {"report", nullptr}},
};

// A result under another name (report-NAME.html, evaluation-NAME.json, as the docs suggest) known by its first bytes,
// as each command writes them (review: `evaluate -o RUN/report-again.html` replaced a report with a text); null for
// anything else.
const RunResult* result_by_content(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string head(4096, '\0');  // an evaluation text may open with a caveat (NOTE: ...) before its counts
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    const auto named = [](const char* name) {
        return &*std::find_if(std::begin(kRunResults), std::end(kRunResults),
                              [&](const RunResult& r) { return std::string_view(r.file) == name; });
    };
    if (head.starts_with("<!DOCTYPE html") && head.find("rollsense") != std::string::npos) return named("report.html");
    if (head.find("\"format\": \"rollsense-evaluation\"") != std::string::npos) return named("evaluation.json");
    static const std::regex evaluation_text(R"((^|\n)trials \d+, (clean|used) \d+, classes \d+\n)");  // after a NOTE
    if (std::regex_search(head, evaluation_text)) return named("evaluation.txt");
    if (head.starts_with("rollsense-")) return named("model.rsm");
    if (head.starts_with("trial_id,object,")) return named("features.csv");
    return nullptr;
}

// Empty when `command` may write `file`; else why not: a result that would land in another dataset's folder than the
// input's, where it would pass for that dataset's own (review: `train D -o W/model.rsm`; predict then judged W's
// trials against D's training range), or an existing result another command wrote.
std::string replaces_other_result(const char* command, const std::filesystem::path& input,
                                  const std::filesystem::path& file) {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (const auto& r : kRunResults) {
        if (file.filename() != r.file) continue;
        // Whether the file exists yet or not (review); folders through links, as predict reads them. A missing input
        // is said by the command itself.
        const auto folder = fs::weakly_canonical(fs::absolute(file, ec).parent_path(), ec);
        const auto own = fs::is_directory(input, ec) ? fs::weakly_canonical(input, ec)
                                                     : fs::weakly_canonical(input, ec).parent_path();
        if (fs::exists(input, ec) && holds_dataset(folder) && folder != own)
            return "-o " + file.string() + ": " + r.what + " made from " + input.string() + " would land in the dataset " +
                   folder.string() + " and pass for its own; give -o another name";
        if (!fs::is_regular_file(file, ec)) return {};
        for (const char* writer : r.writers)
            if (writer && std::string_view(writer) == command) return {};
        return "-o " + file.string() + " would replace, with another kind of file, " + r.what + " (by its name: `rollsense " +
               r.writers[0] + "` writes it); give -o another name, or delete it first if it is unwanted";
    }
    if (!fs::is_regular_file(file, ec)) return {};
    const RunResult* r = result_by_content(file);
    if (!r || std::ranges::any_of(r->writers, [&](const char* w) { return w && std::string_view(w) == command; })) return {};
    return "-o " + file.string() + " would replace, with another kind of file, " + r->what + " that `rollsense " +
           r->writers[0] + "` wrote there (by its content); give -o another name, or delete it first if it is unwanted";
}
}  // namespace

int check_output_files(const char* command, const std::filesystem::path& input,
                       const std::vector<std::filesystem::path>& outputs) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const bool dataset = fs::is_directory(input, ec);
    for (const auto& file : outputs) {
        // Review: `evaluate in.csv -o in.csv` replaced the features it read with the evaluation.
        if (!dataset && fs::exists(file, ec) && fs::equivalent(input, file, ec)) {
            std::fprintf(stderr, "rollsense %s: -o %s is the file %s reads; give -o another name\n", command,
                         file.c_str(), command);
            return kExitUsage;
        }
        // A FIFO, a terminal or /dev/stdout takes one file in place (rollsense/atomic_file.hpp); the files written
        // beside it would land in its folder (review: /dev/stdout.json as root).
        if (outputs.size() > 1 && landing_of(file).written_in_place()) {
            const std::string which = file == outputs.front() ? "" : " (beside -o " + outputs.front().string() + ")";
            std::fprintf(stderr, "rollsense %s: %s%s is not a regular file; %s writes %zu files side by side (%s and "
                                 "%s); name a file in a folder\n",
                         command, file.c_str(), which.c_str(), command, outputs.size(),
                         outputs.front().filename().c_str(), outputs.back().filename().c_str());
            return kExitUsage;
        }
        // The input's files, and any other dataset's the output lands in (review: -o OTHER/manifest.csv replaced
        // another dataset's manifest with a features table).
        std::vector<std::filesystem::path> datasets;
        if (dataset) datasets.push_back(input);
        const auto folder = fs::absolute(file, ec).parent_path();
        for (const auto& dir : {folder, folder.parent_path()})  // beside the file, or the file under its trials/
            if (holds_dataset(dir)) datasets.push_back(dir);
        for (const auto& dir : datasets)
            if (auto st = check_not_dataset_file(file, dir, "-o"); !st) {
                std::fprintf(stderr, "rollsense %s: %s\n", command, st.message().c_str());
                return kExitUsage;
            }
        if (const auto why = replaces_other_result(command, input, file); !why.empty()) {
            std::fprintf(stderr, "rollsense %s: %s\n", command, why.c_str());
            return kExitUsage;
        }
        if (auto st = check_can_write(file); !st) {
            std::fprintf(stderr, "rollsense %s: %s\n", command, st.message().c_str());
            return exit_code_for(st.code());
        }
    }
    return kExitOk;
}

std::string output_option(const Args& args) {
    const std::string out = args.option("--output", "-o");
    return out == "-" ? "/dev/stdout" : out;
}

}  // namespace rollsense::cli
