// CSV as RFC 4180 writes it (comma separator, double-quoted fields with ""
// escapes, header row), which MATLAB's readtable and pandas' read_csv read
// without options. Every error names the file, the line and the column.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rollsense/status.hpp"

namespace rollsense::csv {

// Bounds of one record, far above what rollsense writes (a trial row is well
// under 1 kB; run-info.csv cuts a status at 64 KiB; a trial's extras are at
// most 64 KiB): past them a file is damaged or not ours, and is refused before
// it costs more memory (a line of commas would cost 32 bytes per byte).
inline constexpr std::size_t kMaxRecordBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxRecordFields = 100000;

// Text from a file as a message quotes it: bytes outside printable ASCII as
// \xNN, and past `limit` bytes cut, with the length ("1234567890… (5000000 bytes)").
std::string excerpt(std::string_view text, std::size_t limit = 60);

// Streaming reader: one record at a time, so large files never load whole.
class Reader {
public:
    static Result<Reader> open(const std::filesystem::path& file);

    const std::vector<std::string>& header() const { return header_; }
    // Index of a header column, or an error naming the file and the column wanted.
    Result<std::size_t> column(std::string_view name) const;
    // Reads the next record into `fields`; returns false at end of file. A record
    // with another field count than the header is an error naming its line.
    Result<bool> next(std::vector<std::string>& fields);
    // 1-based line number where the last record returned by next() started.
    std::size_t line() const { return record_line_; }
    const std::filesystem::path& path() const { return path_; }

    // "file:line: column 'name': message", the form of every parse error.
    std::string where(std::size_t column_index) const;

    // Strict number parsing: the whole field must be a number ("NaN" and "nan"
    // are accepted as NaN; empty is an error).
    Result<double> number(const std::vector<std::string>& fields, std::size_t column_index) const;
    // Strict whole-number parsing in [min, max]: digits only (no sign other than
    // a leading '-' when min < 0, no exponent, no fraction), so "1e30", "inf" and
    // out-of-range values are errors naming the file, line and column.
    Result<std::int64_t> integer(const std::vector<std::string>& fields, std::size_t column_index, std::int64_t min,
                                 std::int64_t max) const;
    Result<std::uint64_t> unsigned_integer(const std::vector<std::string>& fields, std::size_t column_index,
                                           std::uint64_t max = UINT64_MAX) const;

private:
    Reader() = default;
    Result<bool> read_record(std::vector<std::string>& fields);
    Result<bool> parse_record(std::vector<std::string>& fields);

    std::filesystem::path path_;
    std::shared_ptr<std::ifstream> in_;
    std::vector<std::string> header_;
    std::size_t next_line_ = 1;
    std::size_t record_line_ = 0;
};

// A whole file at once (a manifest checked for a torn last line, a shard's
// files copied by merge), with Reader::open's errors: a folder, a missing file
// and an unreadable one are each refused naming it.
Result<std::string> read_file(const std::filesystem::path& file);

// Parse a whole number field; `where` goes in the error.
Result<double> parse_number(std::string_view text, const std::string& where);

// Parse a whole number field in [min, max] / [0, max]; `where` goes in the error.
Result<std::int64_t> parse_integer(std::string_view text, std::int64_t min, std::int64_t max, const std::string& where);
Result<std::uint64_t> parse_unsigned(std::string_view text, std::uint64_t max, const std::string& where);

// The "key,value" files of a dataset (run-info.csv, run-config.csv), in file
// order. A missing file reads as empty: older datasets have none.
using KeyValues = std::vector<std::pair<std::string, std::string>>;
Result<KeyValues> read_key_values(const std::filesystem::path& file);

// A key-value file names each key once: an error at the reader's line for `key` if `seen` (key → its line) has it
// already (which of two would hold is not for a reader to guess), else `key` is added.
Status refuse_repeated_key(std::unordered_map<std::string, std::size_t>& seen, const Reader& reader,
                           std::size_t key_column, const std::string& key);
// "key,value\n" and one row per entry: the content of such a file.
std::string format_key_values(const KeyValues& entries);

// Quote a field if it needs quoting.
std::string escape(std::string_view field);
// Append one record (escaped, comma separated, '\n' terminated).
void append_row(std::string& out, const std::vector<std::string>& fields);
// Shortest text that reads back as the same double ("%.17g"-exact, but short
// for round values), so files are byte-identical for identical data.
std::string format_number(double value);
// A measured value with 9 significant digits: far finer than any sensor's
// resolution, and less than half the bytes of an exact double. Deterministic:
// exactly printf's "%.9g" (std::to_chars with precision 9 is defined as it).
std::string format_sample(double value);
// The same two, appended to `out` without a temporary string (trial files).
void append_number(std::string& out, double value);
// Returns the value as the text reads back (parse_number of what was appended):
// a trial's as-written samples without parsing them again.
double append_sample(std::string& out, double value);

}  // namespace rollsense::csv
