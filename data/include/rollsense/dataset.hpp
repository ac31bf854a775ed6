// A recorded dataset on disk, the format every tool of rollsense reads and
// writes (docs/dataset-format.md describes it for MATLAB and pandas users).
//
//   <dir>/dataset-info.csv   key,value: format, version, sample rate, channel and
//                            joint column names, channel units, profile, seed
//                            (deterministic)
//   <dir>/manifest.csv       one row per trial, in recording order
//   <dir>/trials/<id>.csv    time,<channels...>,<joints...>,valid  (time from the
//                            recording's start; values with 9 significant digits)
//   <dir>/run-info.csv       wall-clock provenance (date, command line, host);
//                            kept apart so the rest is byte-identical per seed;
//                            a resume keeps the earlier run's as run-info.N.csv
//   <dir>/run-config.csv     what decided the trials (script, profile, --set,
//                            seed, version; rollsense/run_config.hpp): --resume
//                            refuses a run that differs
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "rollsense/atomic_file.hpp"
#include "rollsense/directory_lock.hpp"
#include "rollsense/run_config.hpp"
#include "rollsense/status.hpp"
#include "rollsense/types.hpp"

namespace rollsense {

inline constexpr const char* kDatasetFormat = "rollsense-dataset";
inline constexpr int kDatasetFormatVersion = 1;

struct DatasetInfo {
    double sample_rate_hz = 31.1;
    std::vector<std::string> channels;  // sensor channel columns, e.g. ch1 ch2 ch3
    std::vector<std::string> channel_units;  // their units, same order ("1" = unitless); empty = not stated
    // The three channels the identification reads, when the dataset has more
    // than one sensor (the profile's identification_channels); empty = not named.
    std::vector<std::string> identification_channels;
    std::vector<std::string> joints;    // recorded joint position columns, e.g. sensing_finger
    std::string profile;
    std::uint64_t seed = 0;
    std::string software_version;
    RunConfig run_config;  // written to run-config.csv by the writer; empty: none written, none checked
};

// One trial's samples, column-major.
struct TrialData {
    std::vector<double> time;                   // seconds on the run clock
    std::vector<std::vector<double>> channels;  // [channel][sample]
    std::vector<std::vector<double>> joints;    // [joint][sample]
    std::vector<std::uint8_t> valid;            // 1 = every channel read fine

    std::size_t samples() const { return time.size(); }
};

struct TrialRecord {
    TrialInfo info;
    std::string file;             // relative to the dataset folder, e.g. trials/C1-v10-r001.csv
    std::size_t samples = 0;
    std::size_t invalid_samples = 0;
    std::size_t manifest_line = 0;  // the line of manifest.csv that lists it (0: not read from one)
};

class DatasetReader {
public:
    // What open() does with a manifest row whose trial file is missing: a reader
    // refuses the dataset (naming the row and the way out); a resume keeps the
    // row, whose load() then fails, so that the trial is recorded again in its place.
    enum class MissingTrialFile { refuse, keep_listed };

    // Reads dataset-info.csv (optional for hand-made datasets: the columns are
    // then inferred from the first trial file) and manifest.csv.
    static Result<DatasetReader> open(const std::filesystem::path& dir,
                                      MissingTrialFile missing = MissingTrialFile::refuse);

    const std::filesystem::path& dir() const { return dir_; }
    const DatasetInfo& info() const { return info_; }
    const std::vector<TrialRecord>& trials() const { return trials_; }
    // Reads and checks one trial file: header matches the dataset's columns,
    // every value numeric, time strictly increasing, row count = manifest.
    Result<TrialData> load(const TrialRecord& record) const;

private:
    std::filesystem::path dir_;
    DatasetInfo info_;
    std::vector<TrialRecord> trials_;
};

enum class DatasetOpenMode {
    create,  // the folder must not hold a dataset yet
    resume,  // continue a dataset with the same info and run configuration; trials
             // listed in the manifest whose file is complete are kept, the others recorded again.
             // A folder refused is left untouched; an accepted one's run-info.csv becomes run-info.N.csv
};

// Writes trials durably, holding a lock on the folder (a second writer is
// refused at once). A batch's trial files are written and synced; then its
// manifest rows are appended (and synced) after the trial files they list, so after a
// crash every trial in the manifest is complete, and a trial file not yet in
// the manifest is simply written again on resume. A crash during an append can
// leave a last line without its line end: the reader refuses such a dataset,
// and resuming cuts that line off (docs/dataset-format.md). The cost of a
// batch is its own size, whatever the dataset's.
//
// Batches of `commit_every` trials are formatted and synced by a background
// thread, so a fast simulated run overlaps its disk syncs with computing the
// next trials. An I/O error is returned by the next add_trial() or flush().
class DatasetWriter {
public:
    static Result<std::unique_ptr<DatasetWriter>> open(const std::filesystem::path& dir, const DatasetInfo& info,
                                                       DatasetOpenMode mode);
    ~DatasetWriter();

    const std::filesystem::path& dir() const { return dir_; }
    const std::vector<TrialRecord>& trials() const { return trials_; }
    bool has_trial(const std::string& trial_id) const;

    // Number of trials collected before a group commit (1 = every trial durable
    // before the call returns).
    void set_commit_every(std::size_t trials) { commit_every_ = trials == 0 ? 1 : trials; }
    // Refuses an id check_trial_id() refuses before anything is queued.
    Status add_trial(TrialRecord record, const TrialData& data);
    // Waits for every queued batch. After a failed write, the error names the
    // trials that were lost (those of the failed batch and of every batch
    // after it: none of them is in the manifest) and how many are durable.
    // A resumed trial recorded again is then put back in its place: the
    // manifest is rewritten (atomically) in the order of an uninterrupted run.
    Status flush();
    // Trials listed in the manifest on disk (resumed ones included): what a
    // run may count as saved.
    std::size_t durable_trials();
    // Trials add_trial() accepted that a failed write lost (not in the manifest).
    std::size_t lost_trials();

    // Called on the writer thread with each trial once it is durable (in the
    // manifest), its values as its file holds them: what DatasetReader::load()
    // would return, without reading the file (features from memory). Set it
    // before the first add_trial(); it must not call back into the writer.
    using DurableObserver = std::function<void(const DatasetInfo&, const TrialRecord&, const TrialData&)>;
    void set_on_durable(DurableObserver observer) { on_durable_ = std::move(observer); }

    // Provenance outside the deterministic files.
    Status write_run_info(const std::vector<std::pair<std::string, std::string>>& entries);

private:
    struct Trial {
        TrialRecord record;
        TrialData data;
    };
    struct Batch {
        std::vector<Trial> trials;
        std::string manifest_rows;  // the rows of these trials, appended once their files are durable
        std::size_t listed = 0;     // trials the manifest lists after this batch
    };
    DatasetWriter() = default;
    std::string manifest_text() const;
    void hand_over();           // pending trials → the writer thread
    void writer_loop();
    Status take_error();
    Status restore_order();  // flush(), writer idle, mutex_ held
    Status error_locked() const;  // error_ with the lost trials named; mutex_ held

    DirectoryLock lock_;  // first member: released after the writer thread has ended
    std::filesystem::path dir_;
    DatasetInfo info_;
    std::vector<TrialRecord> trials_;
    std::unordered_map<std::string, bool> ids_;  // of trials_, has_trial() in constant time: on disk when opened?
    std::vector<std::string> resumed_order_;  // the manifest's ids when resumed, if it dropped any: their places
    Batch pending_;
    std::size_t commit_every_ = 1;
    DurableObserver on_durable_;

    std::thread writer_;
    std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::deque<Batch> queue_;
    bool busy_ = false, stopping_ = false;
    Status error_;
    mutable bool error_told_ = false;  // error_locked() returned error_ to a caller
    std::vector<std::string> lost_;  // trials of batches that failed or were skipped after a failure
    std::size_t durable_ = 0;        // trials in the manifest on disk
};

// Render a trial as its CSV file content (used by the writer and by tests).
// With `as_written`, also the trial as a reader loads it back from that text
// (values to 9 significant digits), without parsing a file.
std::string format_trial_csv(const DatasetInfo& info, const TrialData& data, TrialData* as_written = nullptr);

}  // namespace rollsense
