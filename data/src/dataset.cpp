#include "rollsense/dataset.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "rollsense/csv.hpp"
#include "rollsense/dataset_files.hpp"
#include "rollsense/log.hpp"
#include "rollsense/run_config.hpp"
#include "rollsense/shard.hpp"
#include "rollsense/trial_id.hpp"

namespace rollsense {
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kManifestColumns = {"trial_id", "file",    "object",          "speed",
                                                    "repetition", "seed", "samples", "invalid_samples",
                                                    "mount",    "index_in_mount", "extra"};

std::string join(const std::vector<std::string>& v, char sep) {
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i) out += (i ? std::string(1, sep) : "") + v[i];
    return out;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    if (s.empty()) return out;
    std::string cur;
    for (char c : s) {
        if (c == sep) {
            out.push_back(cur);
            cur.clear();
        } else {
            cur.push_back(c);
        }
    }
    out.push_back(cur);
    return out;
}

// "key=value;key=value" for the manifest's free-form column.
std::string format_extra(const std::map<std::string, std::string>& extra) {
    std::string out;
    for (const auto& [k, v] : extra) out += (out.empty() ? "" : ";") + k + "=" + v;
    return out;
}
std::map<std::string, std::string> parse_extra(const std::string& text) {
    std::map<std::string, std::string> out;
    for (const auto& item : split(text, ';')) {
        auto eq = item.find('=');
        if (eq != std::string::npos) out[item.substr(0, eq)] = item.substr(eq + 1);
    }
    return out;
}

std::string format_info(const DatasetInfo& info) {
    std::string out;
    csv::append_row(out, {"key", "value"});
    csv::append_row(out, {"format", kDatasetFormat});
    csv::append_row(out, {"format_version", std::to_string(kDatasetFormatVersion)});
    csv::append_row(out, {"sample_rate_hz", csv::format_number(info.sample_rate_hz)});
    csv::append_row(out, {"channels", join(info.channels, ' ')});
    if (!info.channel_units.empty()) {
        // Space-separated like the names: a unit with a space gets '_', an unstated one '?'.
        std::vector<std::string> units;
        for (auto u : info.channel_units) {
            std::replace(u.begin(), u.end(), ' ', '_');
            units.push_back(u.empty() ? "?" : u);
        }
        csv::append_row(out, {"channel_units", join(units, ' ')});
    }
    if (!info.identification_channels.empty())
        csv::append_row(out, {"identification_channels", join(info.identification_channels, ' ')});
    csv::append_row(out, {"joints", join(info.joints, ' ')});
    csv::append_row(out, {"profile", info.profile});
    csv::append_row(out, {"seed", std::to_string(info.seed)});
    csv::append_row(out, {"software_version", info.software_version});
    return out;
}

// Far above any sensor rollsense reads (the barometers sample at ~31 Hz).
constexpr double kMaxSampleRateHz = 1e6;

Result<DatasetInfo> read_info(const fs::path& file) {
    auto reader = csv::Reader::open(file);
    if (!reader) return reader.error();
    auto key_col = reader->column("key");
    auto val_col = reader->column("value");
    if (!key_col) return key_col.error();
    if (!val_col) return val_col.error();
    DatasetInfo info;
    std::vector<std::string> f;
    bool format_seen = false;
    std::unordered_map<std::string, std::size_t> line_of;  // review: a key given twice, the last one silently won
    for (;;) {
        auto more = reader->next(f);
        if (!more) return more.error();
        if (!*more) break;
        const auto& key = f[*key_col];
        const auto& value = f[*val_col];
        if (auto s = csv::refuse_repeated_key(line_of, *reader, *key_col, key); !s) return s.error();
        if (key == "format") {
            if (value != kDatasetFormat)
                return Error{ErrorCode::parse_error, reader->where(*val_col) + ": format is '" + value +
                                                         "', expected '" + kDatasetFormat + "'"};
            format_seen = true;
        } else if (key == "format_version") {
            auto v = reader->integer(f, *val_col, 1, INT32_MAX);
            if (!v) return v.error();
            if (*v > kDatasetFormatVersion)
                return Error{ErrorCode::parse_error, reader->where(*val_col) + ": format version " + value +
                                                         " is newer than this rollsense reads (" +
                                                         std::to_string(kDatasetFormatVersion) +
                                                         "); upgrade rollsense"};
        } else if (key == "sample_rate_hz") {
            auto v = reader->number(f, *val_col);
            if (!v) return v.error();
            // Every reader divides by it (sample periods, windows in samples).
            if (!std::isfinite(*v) || *v <= 0.0 || *v > kMaxSampleRateHz)
                return Error{ErrorCode::parse_error, reader->where(*val_col) + ": sample rate " + value +
                                                         " Hz is not in (0, " + csv::format_number(kMaxSampleRateHz) +
                                                         "]"};
            info.sample_rate_hz = *v;
        } else if (key == "channels" || key == "joints") {
            // Column names: a name given twice would blame every trial file for the columns it lacks (review).
            auto& names = key == "channels" ? info.channels : info.joints;
            names = split(value, ' ');
            std::unordered_set<std::string> seen;
            for (const auto& name : names)
                if (!seen.insert(name).second)
                    return Error{ErrorCode::parse_error, reader->where(*val_col) + ": " + key + " names '" +
                                                             csv::excerpt(name) + "' twice; each column once"};
        } else if (key == "channel_units") {
            info.channel_units = split(value, ' ');
        } else if (key == "identification_channels") {
            info.identification_channels = split(value, ' ');
        } else if (key == "profile") {
            info.profile = value;
        } else if (key == "seed") {
            auto v = reader->unsigned_integer(f, *val_col);
            if (!v) return v.error();
            info.seed = *v;
        } else if (key == "software_version") {
            info.software_version = value;
        }
    }
    if (!format_seen) return Error{ErrorCode::parse_error, file.string() + ": no 'format' row; not a rollsense dataset"};
    if (!info.channel_units.empty() && info.channel_units.size() != info.channels.size())
        return Error{ErrorCode::parse_error, file.string() + ": 'channel_units' gives " +
                                                 std::to_string(info.channel_units.size()) + " units for " +
                                                 std::to_string(info.channels.size()) +
                                                 " channels; give one per channel, in the order of 'channels'"};
    return info;
}

// Counts of a trial's samples: far above any real recording, far below what overflows.
constexpr std::uint64_t kMaxCount = 1'000'000'000;

// The columns a manifest row is read from (SIZE_MAX: an optional column it lacks).
using ManifestColumns = std::vector<std::size_t>;

// One manifest row, the inverse of append_manifest_row.
Result<TrialRecord> parse_manifest_row(const csv::Reader& reader, const std::vector<std::string>& f,
                                       const ManifestColumns& col) {
    auto integer = [&](std::size_t c, std::uint64_t max = kMaxCount) -> Result<std::uint64_t> {
        if (c == SIZE_MAX) return std::uint64_t{0};
        return reader.unsigned_integer(f, c, max);
    };
    TrialRecord r;
    r.info.id = f[col[0]];
    r.file = f[col[1]];
    r.info.object = f[col[2]];
    r.info.speed = f[col[3]];
    auto rep = integer(col[4], INT32_MAX);
    if (!rep) return rep.error();
    r.info.repetition = static_cast<int>(*rep);
    if (col[5] != SIZE_MAX) {
        auto seed = integer(col[5], UINT64_MAX);
        if (!seed) return seed.error();
        r.info.seed = *seed;
    }
    auto samples = integer(col[6]);
    if (!samples) return samples.error();
    r.samples = static_cast<std::size_t>(*samples);
    auto invalid = integer(col[7]);
    if (!invalid) return invalid.error();
    r.invalid_samples = static_cast<std::size_t>(*invalid);
    if (col[10] != SIZE_MAX) r.info.extra = parse_extra(f[col[10]]);
    for (std::size_t k = 0; k < kProtocolKeys.size(); ++k)
        if (col[8 + k] != SIZE_MAX && !f[col[8 + k]].empty()) r.info.extra[kProtocolKeys[k]] = f[col[8 + k]];
    if (r.info.id.empty()) return Error{ErrorCode::parse_error, reader.where(col[0]) + ": empty trial id"};
    // A manifest names files inside its dataset folder only.
    const fs::path listed(r.file);
    if (r.file.empty() || listed.is_absolute() ||
        std::any_of(listed.begin(), listed.end(), [](const fs::path& part) { return part == ".."; }))
        return Error{ErrorCode::parse_error, reader.where(col[1]) + ": '" + r.file +
                                                 "' is not a path inside the dataset folder (relative, no '..')"};
    return r;
}

Result<std::vector<TrialRecord>> read_manifest(const fs::path& file) {
    auto reader = csv::Reader::open(file);
    if (!reader) return reader.error();
    ManifestColumns col;
    for (const auto& name : kManifestColumns) {
        if (name == "extra" || name == "invalid_samples" || name == "seed" || name == "mount" ||
            name == "index_in_mount") {
            auto c = reader->column(name);
            col.push_back(c ? *c : SIZE_MAX);  // optional in hand-made manifests
            continue;
        }
        auto c = reader->column(name);
        if (!c) return c.error();
        col.push_back(*c);
    }
    std::vector<TrialRecord> out;
    std::unordered_set<std::string> ids;
    std::unordered_map<std::string, std::string> listed_by;  // trial file → the trial id listing it
    std::vector<std::string> f;
    for (;;) {
        auto more = reader->next(f);
        if (!more) return more.error();
        if (!*more) break;
        auto r = parse_manifest_row(*reader, f, col);
        if (!r) return r.error();
        r->manifest_line = reader->line();
        if (!ids.insert(r->info.id).second)
            return Error{ErrorCode::parse_error,
                         reader->where(col[0]) + ": trial id '" + r->info.id + "' appears twice"};
        // Review: one recording listed twice sat in a training fold and a test fold at once.
        if (const auto [at, fresh] = listed_by.emplace(fs::path(r->file).lexically_normal().string(), r->info.id);
            !fresh)
            return Error{ErrorCode::parse_error, reader->where(col[1]) + ": trial '" + r->info.id + "' names the file " +
                                                     r->file + ", which trial '" + at->second + "' names too: " +
                                                     "each trial has a file of its own"};
        out.push_back(std::move(*r));
    }
    return out;
}

// One manifest row, '\n' terminated: what a batch appends for each of its trials.
void append_manifest_row(std::string& out, const TrialRecord& t) {
    auto extra = t.info.extra;
    std::vector<std::string> protocol;
    for (const auto& key : kProtocolKeys) {
        auto it = extra.find(key);
        protocol.push_back(it == extra.end() ? "" : it->second);
        if (it != extra.end()) extra.erase(it);
    }
    csv::append_row(out, {t.info.id, t.file, t.info.object, t.info.speed, std::to_string(t.info.repetition),
                          std::to_string(t.info.seed), std::to_string(t.samples), std::to_string(t.invalid_samples),
                          protocol[0], protocol[1], format_extra(extra)});
}

// A manifest is appended to batch by batch; a crash in the middle of an
// append can leave its last row without its line end. Returns the size of the
// file without that torn row and the number of the line it starts on, or
// nothing when the file ends with a row's line end (or is empty). A row ends
// at a line end outside quotes: a quoted field may hold line ends (an `extra`
// value), so a crash just after one of those leaves a file that ends with a
// line end inside an unclosed quote, which is torn too.
struct TornLine {
    std::uintmax_t keep_bytes = 0;
    std::size_t line = 0;
};
Result<std::optional<TornLine>> find_torn_line(const fs::path& file) {
    auto read = csv::read_file(file);
    if (!read) return read.error();
    const std::string& text = *read;
    std::size_t row_end = 0;  // bytes up to the last line end outside quotes
    bool quoted = false;      // a doubled quote inside a field toggles twice: no net change
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '"') quoted = !quoted;
        else if (text[i] == '\n' && !quoted) row_end = i + 1;
    }
    if (row_end == text.size()) return std::optional<TornLine>{};
    TornLine torn;
    torn.keep_bytes = row_end;
    torn.line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(row_end), '\n'));
    return std::optional<TornLine>{torn};
}

// Resuming: the earlier run's run-info.csv becomes run-info.N.csv (N one past
// the highest there, from 1), so every run of the dataset keeps its record.
Status keep_earlier_run_info(const fs::path& dir) {
    std::error_code ec;
    if (!fs::exists(dir / kRunInfoFile, ec)) return {};
    std::size_t last = 0;
    for (const auto& entry : fs::directory_iterator(dir, ec))
        last = std::max(last, earlier_run_number(entry.path().filename().string()));
    if (ec) return {ErrorCode::io_error, dir.string() + ": cannot list: " + ec.message()};
    return rename_durable(dir / kRunInfoFile, dir / earlier_run_info_name(last + 1));
}

// Resuming: cut a torn last line off the manifest (the trial it listed is
// recorded again, as is any trial whose file the manifest does not list).
Status drop_torn_line(const fs::path& manifest) {
    std::error_code ec;
    if (!fs::exists(manifest, ec)) return {};
    auto torn = find_torn_line(manifest);
    if (!torn) return torn.error();
    if (!*torn) return {};
    log_warning("dataset", manifest.string() + ":" + std::to_string((*torn)->line) +
                               ": the last row has no line end (a crash while listing a trial); it is dropped and "
                               "its trial recorded again");
    if ((*torn)->keep_bytes == 0) {  // the header itself was cut: write it again
        std::string header;
        csv::append_row(header, kManifestColumns);
        return write_file_atomic(manifest, header);
    }
    fs::resize_file(manifest, (*torn)->keep_bytes, ec);
    if (ec) return {ErrorCode::io_error, manifest.string() + ": cannot cut the torn last line: " + ec.message()};
    return {};
}

}  // namespace

std::string format_trial_csv(const DatasetInfo& info, const TrialData& data, TrialData* as_written) {
    std::string out;
    out.reserve(64 + data.samples() * (12 * (2 + info.channels.size() + info.joints.size())));
    std::vector<std::string> header{"time"};
    header.insert(header.end(), info.channels.begin(), info.channels.end());
    header.insert(header.end(), info.joints.begin(), info.joints.end());
    header.push_back("valid");
    csv::append_row(out, header);
    if (as_written) {
        *as_written = TrialData{};
        as_written->channels.resize(data.channels.size());
        as_written->joints.resize(data.joints.size());
    }
    // Appends one value; with `as_written`, also the value DatasetReader::load()
    // reads back from the text: samples have 9 significant digits, and the
    // shortest form of a finite time reads back as itself.
    auto put = [&out](double value, bool sample, std::vector<double>* back) {
        const std::size_t from = out.size();
        const double read_back = sample ? csv::append_sample(out, value) : (csv::append_number(out, value), value);
        if (!back) return;
        const bool known = sample || std::isfinite(value);  // else "NaN" / "Inf", as parse_number reads them
        back->push_back(known ? read_back : csv::parse_number(std::string_view(out).substr(from), {}).value());
    };
    for (std::size_t i = 0; i < data.samples(); ++i) {
        put(data.time[i], false, as_written ? &as_written->time : nullptr);
        for (std::size_t c = 0; c < data.channels.size(); ++c) {
            out.push_back(',');
            put(data.channels[c][i], true, as_written ? &as_written->channels[c] : nullptr);
        }
        for (std::size_t j = 0; j < data.joints.size(); ++j) {
            out.push_back(',');
            put(data.joints[j][i], true, as_written ? &as_written->joints[j] : nullptr);
        }
        const bool valid = !(i < data.valid.size() && !data.valid[i]);
        out += valid ? ",1\n" : ",0\n";
        if (as_written) as_written->valid.push_back(valid ? 1 : 0);
    }
    return out;
}

// ------------------------------------------------------------------ reader --

Result<DatasetReader> DatasetReader::open(const fs::path& dir, MissingTrialFile missing) {
    DatasetReader r;
    r.dir_ = dir;
    std::error_code ec;
    if (!fs::is_directory(dir, ec))  // user review: a features CSV given as a dataset was "no such dataset folder"
        return Error{ErrorCode::not_found, dir.string() + (fs::exists(dir, ec) ? ": a file, not a dataset folder (give "
                                                                                  "the folder a run recorded)"
                                                                                : ": no such dataset folder")};
    // A manifest rollsense wrote (beside its dataset-info.csv) whose last line
    // lacks its line end was cut by a crash while a batch was being listed: that
    // trial may be incomplete, so the dataset is refused until --resume drops it.
    const bool recorded = fs::exists(dir / "dataset-info.csv", ec);
    if (recorded && fs::exists(dir / "manifest.csv", ec)) {
        auto torn = find_torn_line(dir / "manifest.csv");
        if (!torn) return torn.error();
        if (*torn)
            return Error{ErrorCode::parse_error,
                         (dir / "manifest.csv").string() + ":" + std::to_string((*torn)->line) +
                             ": the last row has no line end: the recording was interrupted while listing a trial. "
                             "Continue the run that recorded " + dir.string() + " with --resume --out " + dir.string() +
                             " (it drops that line and records the trial again)"};
    }
    if (!fs::exists(dir / "manifest.csv", ec))  // a dataset that lost its list (review: "holds no dataset" misled)
        return Error{ErrorCode::not_found,
                     fs::exists(dir / "dataset-info.csv", ec)
                         ? dir.string() + " has a dataset-info.csv but no manifest.csv, the list of its trials: restore "
                                          "it from a copy (its rows name trials/*.csv; docs/dataset-format.md)"
                         : dir.string() + " holds no dataset (no manifest.csv): give a folder that 'rollsense run ... "
                                          "--out DIR' recorded (docs/dataset-format.md)"};
    auto manifest = read_manifest(dir / "manifest.csv");
    if (!manifest) return manifest.error();
    r.trials_ = std::move(*manifest);
    for (const auto& t : r.trials_)
        if (missing == MissingTrialFile::refuse && !fs::exists(dir / t.file, ec)) {
            const std::string line = std::to_string(t.manifest_line);
            return Error{ErrorCode::not_found,
                         (dir / "manifest.csv").string() + ":" + line + ": trial '" + t.info.id + "' is listed, but " +
                             (dir / t.file).string() + " is missing. Put the file back, " +
                             (recorded ? "record it again in its place with '" + resume_command(dir) + "', "
                                      : std::string()) +
                             "or delete line " + line + " of manifest.csv to use the dataset without that trial"};
        }
    if (recorded) {
        auto info = read_info(dir / "dataset-info.csv");
        if (!info) return info.error();
        r.info_ = std::move(*info);
    } else {
        // A hand-made dataset: columns come from the first trial file; every
        // column between time and valid whose name starts with "ch" is a channel.
        if (r.trials_.empty())
            return Error{ErrorCode::parse_error, (dir / "manifest.csv").string() + ": lists no trials"};
        auto first = csv::Reader::open(dir / r.trials_.front().file);
        if (!first) return Error{ErrorCode::not_found, (dir / "manifest.csv").string() + ": trial '" +
                                                           r.trials_.front().info.id + "': " + first.error().message};
        for (const auto& h : first->header()) {
            if (h == "time" || h == "valid") continue;
            (h.rfind("ch", 0) == 0 ? r.info_.channels : r.info_.joints).push_back(h);
        }
    }
    return r;
}

Result<TrialData> DatasetReader::load(const TrialRecord& record) const {
    auto reader = csv::Reader::open(dir_ / record.file);
    if (!reader) return reader.error();
    auto time_col = reader->column("time");
    if (!time_col) return time_col.error();
    std::vector<std::size_t> ch_cols, joint_cols;
    for (const auto& c : info_.channels) {
        auto col = reader->column(c);
        if (!col)
            return Error{ErrorCode::parse_error, col.error().message + " — the dataset has " +
                                                     std::to_string(info_.channels.size()) + " channels"};
        ch_cols.push_back(*col);
    }
    for (const auto& j : info_.joints) {
        auto col = reader->column(j);
        if (!col) return col.error();
        joint_cols.push_back(*col);
    }
    // A "ch..." column the dataset does not know is a file from another setup
    // (or a hand-made dataset whose files disagree): refuse it rather than
    // silently drop a channel.
    for (const auto& h : reader->header()) {
        if (h.rfind("ch", 0) != 0) continue;
        if (std::find(info_.channels.begin(), info_.channels.end(), h) != info_.channels.end() ||
            std::find(info_.joints.begin(), info_.joints.end(), h) != info_.joints.end())
            continue;
        return Error{ErrorCode::parse_error, (dir_ / record.file).string() + ":1: column '" + h +
                                                 "' is not a channel of this dataset, which has " +
                                                 std::to_string(info_.channels.size()) + " (" +
                                                 join(info_.channels, ' ') + "): a file from another setup?"};
    }
    std::size_t valid_col = SIZE_MAX;
    if (auto v = reader->column("valid"); v) valid_col = *v;

    TrialData d;
    d.channels.resize(ch_cols.size());
    d.joints.resize(joint_cols.size());
    // The manifest's count is only a hint for reserving: a row takes at least
    // two bytes per column, so the file's size bounds what is worth reserving
    // (a damaged manifest must not make this allocate gigabytes).
    std::error_code size_ec;
    const auto bytes = fs::file_size(dir_ / record.file, size_ec);
    const std::size_t row_bytes = 2 * (1 + ch_cols.size() + joint_cols.size());
    const std::size_t expected =
        size_ec ? 0 : std::min<std::size_t>(record.samples, static_cast<std::size_t>(bytes / row_bytes));
    d.time.reserve(expected);
    for (auto& c : d.channels) c.reserve(expected);
    std::vector<std::string> f;
    for (;;) {
        auto more = reader->next(f);
        if (!more) return more.error();
        if (!*more) break;
        auto t = reader->number(f, *time_col);
        if (!t) return t.error();
        if (!std::isfinite(*t))
            return Error{ErrorCode::parse_error, reader->where(*time_col) + ": time must be a finite number"};
        if (!d.time.empty() && *t <= d.time.back())
            return Error{ErrorCode::parse_error, reader->where(*time_col) + ": time " + f[*time_col] +
                                                     " does not increase (previous " +
                                                     csv::format_number(d.time.back()) + ")"};
        d.time.push_back(*t);
        for (std::size_t c = 0; c < ch_cols.size(); ++c) {
            auto v = reader->number(f, ch_cols[c]);
            if (!v) return v.error();
            d.channels[c].push_back(*v);
        }
        for (std::size_t j = 0; j < joint_cols.size(); ++j) {
            auto v = reader->number(f, joint_cols[j]);
            if (!v) return v.error();
            d.joints[j].push_back(*v);
        }
        if (valid_col != SIZE_MAX) {
            const auto& v = f[valid_col];
            if (v != "0" && v != "1")
                return Error{ErrorCode::parse_error, reader->where(valid_col) + ": '" + v + "' is not 0 or 1"};
            d.valid.push_back(v == "1" ? 1 : 0);
        } else {
            d.valid.push_back(1);
        }
    }
    if (record.samples != 0 && d.samples() != record.samples)
        return Error{ErrorCode::parse_error, (dir_ / record.file).string() + ": " + std::to_string(d.samples()) +
                                                 " samples, the manifest says " + std::to_string(record.samples) +
                                                 (d.samples() < record.samples
                                                      ? " (a truncated file?)"
                                                      : ": the file has more rows than the manifest lists (rows "
                                                        "added to it, or the manifest edited?)")};
    return d;
}

// ------------------------------------------------------------------ writer --

Result<std::unique_ptr<DatasetWriter>> DatasetWriter::open(const fs::path& dir, const DatasetInfo& info,
                                                           DatasetOpenMode mode) {
    std::unique_ptr<DatasetWriter> w(new DatasetWriter());
    w->dir_ = dir;
    w->info_ = info;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return Error{ErrorCode::io_error, dir.string() + ": cannot create: " + ec.message()};
    auto lock = DirectoryLock::acquire(dir);
    if (!lock) return lock.error();
    w->lock_ = std::move(lock).value();
    const bool exists = holds_dataset(dir);
    if (mode == DatasetOpenMode::create)
        if (auto s = check_no_dataset_in(dir); !s.ok()) return s.error();
    // A resume checks the folder is this run's dataset before it changes
    // anything there: a refused folder stays exactly as it was.
    std::optional<DatasetReader> on_disk;
    auto same_setup = [&](const DatasetInfo& old) -> Status {
        std::string differ;  // each key that differs, with both values (review: only profile and seed were named)
        auto compare = [&](const char* key, const std::string& was, const std::string& now) {
            if (was == now) return;
            differ += (differ.empty() ? "" : "; ") + std::string(key) + " was '" + was + "', this run's '" + now + "'";
        };
        compare("profile", old.profile, info.profile);
        compare("seed", std::to_string(old.seed), std::to_string(info.seed));
        compare("channels", join(old.channels, ' '), join(info.channels, ' '));
        compare("joints", join(old.joints, ' '), join(info.joints, ' '));
        if (old.sample_rate_hz != info.sample_rate_hz)  // shortest round-trip text: two rates never print alike
            compare("sample_rate_hz", csv::format_number(old.sample_rate_hz), csv::format_number(info.sample_rate_hz));
        if (differ.empty()) return {};
        return {ErrorCode::bad_setting, dir.string() + " was recorded with another setup (" + differ +
                                                 "): resume it with the --profile, --seed and --set it was recorded "
                                                 "with, or record into another folder with --out"};
    };
    if (mode == DatasetOpenMode::resume && exists) {
        if (auto s = check_resume_config(dir, info.run_config); !s.ok()) return s.error();
        // Before the torn line is cut: another experiment's manifest is not touched.
        const bool recorded = fs::exists(dir / "dataset-info.csv", ec);
        if (recorded)
            if (auto old = read_info(dir / "dataset-info.csv"); old)  // unreadable: the reader below says why
                if (auto s = same_setup(*old); !s.ok()) return s.error();
        if (auto s = drop_torn_line(dir / "manifest.csv"); !s.ok())
            return Error{s.error().code, "cannot resume: " + s.error().message};
        auto read = DatasetReader::open(dir, DatasetReader::MissingTrialFile::keep_listed);
        if (!read) {  // review: a damaged manifest row or dataset-info.csv was named with no way on
            const std::string way = read.error().code != ErrorCode::parse_error
                                        ? ""
                                        : "; repair or restore that file, or record anew into another --out (a manifest "
                                          "row may also be deleted: a resume records again a trial it does not list)";
            return Error{read.error().code, "cannot resume: " + read.error().message + way};
        }
        if (!recorded)  // a hand-made dataset's setup, inferred from its first trial file
            if (auto s = same_setup(read->info()); !s.ok())  // review: a lost dataset-info.csv read as another setup
                return Error{s.error().code, s.error().message + " (" + (dir / "dataset-info.csv").string() +
                                                 " is missing, so its setup was read from its first trial file: "
                                                 "restore that file if the run wrote one)"};
        // Review: without run-config.csv a resume took any script and --set, then wrote one claiming its own.
        if (!w->info_.run_config.empty() && !fs::exists(dir / kRunConfigFile, ec)) {
            log_warning("dataset", (dir / kRunConfigFile).string() + " is missing: this run's script and --set "
                                   "cannot be checked against the run that recorded the dataset (only its setup in "
                                   "dataset-info.csv is), and none is written now");
            w->info_.run_config.clear();
        } else if (auto was = read_run_config(dir); was && !lists_read_files(*was)) {
            // Recorded before the module and include rows: it keeps none (diff review: today's digests were written,
            // and described the trials recorded earlier too).
            std::erase_if(w->info_.run_config, [](const auto& row) { return is_read_file_key(row.first); });
        }
        on_disk = std::move(*read);
        if (auto s = keep_earlier_run_info(dir); !s.ok()) return s.error();
    }
    fs::create_directories(dir / "trials", ec);
    if (ec) return Error{ErrorCode::io_error, (dir / "trials").string() + ": cannot create: " + ec.message()};
    remove_stale_temporaries(dir);
    remove_stale_temporaries(dir / "trials");
    if (on_disk) {
        // A trial whose file is missing or not what the manifest says (cut short
        // by a crash or a full disk) is recorded again, not kept.
        for (const auto& t : on_disk->trials()) {
            w->resumed_order_.push_back(t.info.id);
            if (auto loaded = on_disk->load(t); loaded) {
                w->trials_.push_back(t);
                w->ids_.emplace(t.info.id, true);
            } else {
                log_warning("dataset", loaded.error().message + ": trial '" + t.info.id + "' is recorded again");
            }
        }
        if (w->trials_.size() == w->resumed_order_.size()) w->resumed_order_.clear();  // nothing out of place
    }
    w->durable_ = w->trials_.size();
    std::vector<PendingFile> files{{dir / "dataset-info.csv", format_info(info)},
                                   {dir / "manifest.csv", w->manifest_text()}};
    if (!w->info_.run_config.empty()) files.push_back({dir / kRunConfigFile, format_run_config(w->info_.run_config)});
    if (auto s = write_files_atomic(files); !s.ok()) return s.error();
    return w;
}

DatasetWriter::~DatasetWriter() {
    // Logged only when no caller was given the error: one who was reports it (once).
    const bool told = [&] {
        std::lock_guard lock(mutex_);
        return error_told_;
    }();
    if (auto s = flush(); !s.ok() && !told) log_error("dataset", s.error().describe());
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    if (writer_.joinable()) writer_.join();
}

bool DatasetWriter::has_trial(const std::string& trial_id) const { return ids_.count(trial_id) != 0; }

std::string DatasetWriter::manifest_text() const {
    std::string out;
    csv::append_row(out, kManifestColumns);
    for (const auto& t : trials_) append_manifest_row(out, t);
    return out;
}

Status DatasetWriter::take_error() {
    std::lock_guard lock(mutex_);
    return error_locked();
}

Status DatasetWriter::error_locked() const {
    if (error_.ok()) return error_;
    error_told_ = true;
    std::string ids;
    for (std::size_t i = 0; i < lost_.size() && i < 20; ++i) ids += (i ? ", " : "") + lost_[i];
    if (lost_.size() > 20) ids += ", ... (" + std::to_string(lost_.size() - 20) + " more)";
    std::string lost = lost_.empty() ? std::string()
                                     : "; " + std::to_string(lost_.size()) + " trial(s) not saved: " + ids;
    return Error{error_.error().code, error_.error().message + lost + "; " + std::to_string(durable_) +
                                          " trial(s) are safely in " + (dir_ / "manifest.csv").string()};
}

std::size_t DatasetWriter::durable_trials() {
    std::lock_guard lock(mutex_);
    return durable_;
}

std::size_t DatasetWriter::lost_trials() {
    std::lock_guard lock(mutex_);
    return lost_.size();
}

Status DatasetWriter::add_trial(TrialRecord record, const TrialData& data) {
    if (auto s = take_error(); !s.ok()) return s;
    // Checked before anything is queued: an id the filesystem refuses would
    // otherwise fail the whole batch later, losing the other trials in it.
    if (auto s = check_trial_info(record.info); !s.ok()) return s;
    // On disk when opened, or saved in this run (user review: the second read as the first, with a resume's advice).
    if (auto it = ids_.find(record.info.id); it != ids_.end())
        return {ErrorCode::invalid_argument,
                "trial '" + record.info.id + "' " +
                    (it->second ? "is already in " + dir_.string() +
                                      " (a resumed run records only what is not on disk: skip a recorded trial with "
                                      "'if not rs.has_trial(id)', as scripts/paper_experiment.lua does)"
                                : std::string("was saved already in this run (a trial is saved once: begin the next "
                                              "with rs.trial{...} under another id)"))};
    if (data.channels.size() != info_.channels.size() || data.joints.size() != info_.joints.size())
        return {ErrorCode::invalid_argument, "trial '" + record.info.id + "' has " +
                                                 std::to_string(data.channels.size()) + " channels, the dataset " +
                                                 std::to_string(info_.channels.size())};
    record.file = "trials/" + record.info.id + ".csv";
    record.samples = data.samples();
    record.invalid_samples = 0;
    for (auto v : data.valid) record.invalid_samples += v ? 0 : 1;
    append_manifest_row(pending_.manifest_rows, record);
    ids_.emplace(record.info.id, false);
    pending_.trials.push_back({record, data});
    trials_.push_back(std::move(record));
    if (pending_.trials.size() >= commit_every_) hand_over();
    return {};
}

void DatasetWriter::hand_over() {
    if (pending_.trials.empty()) return;
    pending_.listed = trials_.size();
    {
        std::lock_guard lock(mutex_);
        queue_.push_back(std::move(pending_));
        if (!writer_.joinable()) writer_ = std::thread(&DatasetWriter::writer_loop, this);
    }
    pending_ = Batch{};
    wake_.notify_one();
}

void DatasetWriter::writer_loop() {
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;  // stopping, nothing left
        Batch batch = std::move(queue_.front());
        queue_.pop_front();
        busy_ = true;
        const bool failed = !error_.ok();
        lock.unlock();
        Status s;
        if (!failed) {  // after an error nothing more is written: the manifest stays truthful
            std::vector<PendingFile> files;
            files.reserve(batch.trials.size());
            std::vector<TrialData> written(on_durable_ ? batch.trials.size() : 0);  // what the files hold
            for (std::size_t i = 0; i < batch.trials.size(); ++i)
                files.push_back({dir_ / batch.trials[i].record.file,
                                 format_trial_csv(info_, batch.trials[i].data, on_durable_ ? &written[i] : nullptr)});
            // Trial files first (written in place and synced: only the manifest
            // makes them part of the dataset), then the rows that list them,
            // appended and synced: each batch costs its own size only.
            s = write_files_synced(files);
            if (s.ok()) s = append_file_durable(dir_ / "manifest.csv", batch.manifest_rows);
            if (s.ok() && on_durable_)
                for (std::size_t i = 0; i < batch.trials.size(); ++i) on_durable_(info_, batch.trials[i].record, written[i]);
        }
        lock.lock();
        if (s.ok() && !failed) {
            durable_ = batch.listed;
        } else {
            // Every trial of a batch that did not reach the manifest is lost,
            // even those whose files were written: the manifest is what counts.
            if (error_.ok()) error_ = s;
            for (const auto& t : batch.trials) lost_.push_back(t.record.info.id);
        }
        busy_ = false;
        idle_.notify_all();
    }
}

Status DatasetWriter::flush() {
    hand_over();
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [&] { return queue_.empty() && !busy_; });
    if (auto s = restore_order(); !s.ok() && error_.ok()) error_ = s;
    return error_locked();
}

Status DatasetWriter::restore_order() {
    if (resumed_order_.empty() || !error_.ok()) return {};
    // The resumed manifest's trials in their places, then the others in the
    // order they were recorded: the order of an uninterrupted run, which the
    // analysis follows. Every trial listed is durable, so the manifest
    // replaced at once lists the same complete trials, only reordered.
    std::unordered_map<std::string, std::size_t> place;
    for (std::size_t i = 0; i < resumed_order_.size(); ++i) place.emplace(resumed_order_[i], i);
    const auto rank = [&](const TrialRecord& t) {
        const auto it = place.find(t.info.id);
        return it == place.end() ? resumed_order_.size() : it->second;
    };
    auto ordered = trials_;
    std::stable_sort(ordered.begin(), ordered.end(),
                     [&](const TrialRecord& a, const TrialRecord& b) { return rank(a) < rank(b); });
    std::size_t placed = 0;  // resumed trials back in the manifest
    for (const auto& t : ordered) placed += place.count(t.info.id);
    const bool moved = !std::equal(ordered.begin(), ordered.end(), trials_.begin(),
                                   [](const TrialRecord& a, const TrialRecord& b) { return a.info.id == b.info.id; });
    if (moved) {
        std::swap(trials_, ordered);
        if (auto s = write_file_atomic(dir_ / "manifest.csv", manifest_text()); !s.ok()) {
            std::swap(trials_, ordered);
            return s;
        }
    }
    if (placed == resumed_order_.size()) resumed_order_.clear();  // all in place: later trials only append
    return {};
}

Status DatasetWriter::write_run_info(const std::vector<std::pair<std::string, std::string>>& entries) {
    return write_file_atomic(dir_ / kRunInfoFile, csv::format_key_values(entries));
}

}  // namespace rollsense
