#include "analysis/learn/model_header.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "rollsense/csv.hpp"

namespace rollsense::learn {

namespace fs = std::filesystem;

Status check_model_file(const fs::path& model) {
    std::error_code ec;
    if (!fs::exists(model, ec))
        return Error{ErrorCode::not_found, model.string() + ": no such model file (write one with 'rollsense train ... "
                                                            "-o MODEL' or a stock run's rs.analyse)"};
    if (fs::is_directory(model, ec)) {
        const bool stock = fs::exists(model / "model.rsm", ec);
        return Error{ErrorCode::invalid_argument,
                     model.string() + " is a folder, not a model file" +
                         (stock ? "; did you mean " + (model / "model.rsm").string() + "?"
                                : " (MODEL is the file 'rollsense train -o' or a stock run wrote, e.g. DIR/model.rsm)")};
    }
    if (!fs::is_regular_file(model, ec))
        return Error{ErrorCode::invalid_argument, model.string() + " is not a regular file (a pipe, a socket or a device): "
                                                                   "give the model file 'rollsense train -o' wrote"};
    if (fs::file_size(model, ec) == 0 && !ec)
        return Error{ErrorCode::parse_error, model.string() + ": the model file is empty (an interrupted write?); "
                                                              "train it again with 'rollsense train ... -o MODEL'"};
    return {};
}

Result<ModelHeader> read_model_header(const fs::path& model) {
    if (auto s = check_model_file(model); !s.ok()) return s.error();
    std::ifstream file(model, std::ios::binary);
    if (!file) return Error{ErrorCode::io_error, model.string() + ": cannot be opened for reading (check permissions)"};
    std::string head(std::size_t{1} << 20, '\0');  // the header is short: a file of one endless line is not read whole
    file.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(file.gcount()));
    std::istringstream in(head);
    ModelHeader h;
    std::string line;
    std::getline(in, line);
    h.magic = line.substr(0, line.find(' '));
    // The header is short; stop before the numeric body of a large model.
    for (int n = 0; n < 10000 && std::getline(in, line); ++n) {
        if (line.rfind("channel ", 0) == 0) h.channels.push_back(line.substr(8));
        if (line.rfind("series_length ", 0) == 0) {
            auto v = csv::parse_unsigned(line.substr(14), 1u << 24, "series_length");
            if (v) h.series_length = static_cast<std::size_t>(*v);
        }
    }
    return h;
}

Result<std::string> plugin_named_by(const ModelHeader& h, const fs::path& model) {
    const std::string prefix = "rollsense-";
    // A features table or a trial file given first is no model at all (first-day review: told to name a classifier).
    if (h.magic.starts_with("trial_id,") || h.magic.starts_with("time,"))
        return Error{ErrorCode::parse_error, model.string() + ":1: a CSV table, not a model: give the model first "
                                                              "(rollsense predict MODEL INPUT; rollsense train makes one)"};
    if (h.magic.rfind(prefix, 0) != 0 || h.magic.size() == prefix.size())
        return Error{ErrorCode::parse_error, model.string() + ":1: the file does not name its classifier (expected "
                                                              "'rollsense-<plugin> <version>'); give --classifier NAME"};
    std::string name = h.magic.substr(prefix.size());
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
}

std::string named_by_note(const fs::path& model, const std::string& way_out) {
    return " (the plugin named by " + model.string() + "'s first line; " + way_out + ")";
}

}  // namespace rollsense::learn
