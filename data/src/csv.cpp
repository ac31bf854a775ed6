#include "rollsense/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <optional>

namespace rollsense::csv {

namespace {

// A file opened for reading, or the error naming it. A folder opens as a
// stream, and its first read throws from the stream buffer (found by
// fuzz_manifest: a manifest whose file column names trials/; and a manifest.csv
// that is itself a folder), so it is refused before.
Result<std::shared_ptr<std::ifstream>> open_for_reading(const std::filesystem::path& file) {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        return Error{ErrorCode::parse_error, file.string() + ": is a folder, not a CSV file"};
    auto in = std::make_shared<std::ifstream>(file, std::ios::binary);
    if (!*in) {
        if (!std::filesystem::exists(file, ec))
            return Error{ErrorCode::not_found, file.string() + ": no such file"};
        return Error{ErrorCode::io_error, file.string() + ": cannot be opened for reading (check permissions)"};
    }
    return in;
}

}  // namespace

Result<std::string> read_file(const std::filesystem::path& file) {
    auto in = open_for_reading(file);
    if (!in) return in.error();
    try {
        return std::string((std::istreambuf_iterator<char>(**in)), std::istreambuf_iterator<char>());
    } catch (const std::ios_base::failure& e) {
        // As in Reader::read_record: a refused read throws from the stream buffer.
        return Error{ErrorCode::io_error, file.string() + ": cannot be read (" + e.what() + ")"};
    }
}

Result<Reader> Reader::open(const std::filesystem::path& file) {
    Reader r;
    r.path_ = file;
    auto in = open_for_reading(file);
    if (!in) return in.error();
    r.in_ = std::move(in).value();
    // A UTF-8 byte-order mark (Excel's "CSV UTF-8" writes one) is not part of the first column's name, quoted or not.
    char bom[3] = {};
    if (!r.in_->read(bom, 3) || std::memcmp(bom, "\xEF\xBB\xBF", 3) != 0) {
        r.in_->clear();
        r.in_->seekg(0);
    }
    auto got = r.read_record(r.header_);
    if (!got.ok()) return got.error();
    if (!got.value() || (r.header_.size() == 1 && r.header_[0].empty()))
        return Error{ErrorCode::parse_error, file.string() + ":1: the file is empty (a header row is expected)"};
    return r;
}

std::string excerpt(std::string_view text, std::size_t limit) {
    std::string out;
    for (const char ch : text.substr(0, limit)) {
        const auto u = static_cast<unsigned char>(ch);
        if (u >= 0x20 && u < 0x7f) {
            out.push_back(ch);
        } else {
            static const char hex[] = "0123456789abcdef";
            out += {'\\', 'x', hex[u >> 4], hex[u & 15]};
        }
    }
    return text.size() > limit ? out + "… (" + std::to_string(text.size()) + " bytes)" : out;
}

Result<std::size_t> Reader::column(std::string_view name) const {
    for (std::size_t i = 0; i < header_.size(); ++i)
        if (header_[i] == name) return i;
    std::string have;
    for (std::size_t i = 0; i < header_.size() && i < 30; ++i) have += (i ? ", " : "") + excerpt(header_[i]);
    if (header_.size() > 30) have += ", … (" + std::to_string(header_.size()) + " columns)";
    return Error{ErrorCode::parse_error,
                 path_.string() + ":1: no column '" + std::string(name) + "' in the header (columns: " + have + ")"};
}

Result<bool> Reader::read_record(std::vector<std::string>& fields) {
    try {
        return parse_record(fields);
    } catch (const std::ios_base::failure& e) {
        // Reading the stream buffer directly (below), a read the operating
        // system refuses throws instead of setting the stream's badbit.
        return Error{ErrorCode::io_error, path_.string() + ":" + std::to_string(next_line_) + ": cannot be read (" +
                                              e.what() + ")"};
    }
}

Result<bool> Reader::parse_record(std::vector<std::string>& fields) {
    fields.clear();
    record_line_ = next_line_;
    std::string field;
    bool in_quotes = false, any = false, field_was_quoted = false;
    int c;
    std::size_t bytes = 0;
    // The stream buffer directly: istream::get() costs a sentry per character.
    std::streambuf& in = *in_->rdbuf();
    while ((c = in.sbumpc()) != EOF) {
        any = true;
        if (++bytes > kMaxRecordBytes || fields.size() >= kMaxRecordFields)
            return Error{ErrorCode::parse_error,
                         path_.string() + ":" + std::to_string(record_line_) + ": a record longer than " +
                             (bytes > kMaxRecordBytes ? std::to_string(kMaxRecordBytes) + " bytes"
                                                      : std::to_string(kMaxRecordFields) + " fields") +
                             ": a damaged file, or not a CSV file of rollsense (restore it, or give the right file)"};
        if (in_quotes) {
            if (c == '"') {
                if (in.sgetc() == '"') {
                    in.sbumpc();
                    field.push_back('"');
                } else {
                    in_quotes = false;
                }
            } else {
                if (c == '\n') ++next_line_;
                field.push_back(static_cast<char>(c));
            }
            continue;
        }
        if (c == '"' && field.empty() && !field_was_quoted) {
            in_quotes = true;
            field_was_quoted = true;
        } else if (c == ',') {
            fields.push_back(std::move(field));
            field.clear();
            field_was_quoted = false;
        } else if (c == '\r') {
            // tolerate CRLF line ends (files edited on Windows / exported by MATLAB)
        } else if (c == '\n') {
            ++next_line_;
            fields.push_back(std::move(field));
            return true;
        } else {
            field.push_back(static_cast<char>(c));
        }
    }
    if (in_quotes)
        return Error{ErrorCode::parse_error, path_.string() + ":" + std::to_string(record_line_) +
                                                 ": a quoted field is not closed before the end of the file"};
    if (!any) return false;
    fields.push_back(std::move(field));
    return true;
}

Result<bool> Reader::next(std::vector<std::string>& fields) {
    for (;;) {
        auto got = read_record(fields);
        if (!got.ok() || !got.value()) return got;
        if (fields.size() == 1 && fields[0].empty()) continue;  // blank line
        if (fields.size() != header_.size())
            return Error{ErrorCode::parse_error,
                         path_.string() + ":" + std::to_string(record_line_) + ": " + std::to_string(fields.size()) +
                             " fields, the header has " + std::to_string(header_.size()) +
                             " (a truncated or malformed row)"};
        return true;
    }
}

std::string Reader::where(std::size_t column_index) const {
    std::string col = column_index < header_.size() ? excerpt(header_[column_index]) : std::to_string(column_index + 1);
    return path_.string() + ":" + std::to_string(record_line_) + ": column '" + col + "'";
}

Result<double> Reader::number(const std::vector<std::string>& fields, std::size_t column_index) const {
    return parse_number(fields.at(column_index), where(column_index));
}

Result<std::int64_t> Reader::integer(const std::vector<std::string>& fields, std::size_t column_index,
                                     std::int64_t min, std::int64_t max) const {
    return parse_integer(fields.at(column_index), min, max, where(column_index));
}

Result<std::uint64_t> Reader::unsigned_integer(const std::vector<std::string>& fields, std::size_t column_index,
                                               std::uint64_t max) const {
    return parse_unsigned(fields.at(column_index), max, where(column_index));
}

namespace {
std::string_view trimmed(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
    return text;
}

template <typename T>
Result<T> parse_whole(std::string_view text, T min, T max, const std::string& where) {
    text = trimmed(text);
    const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
    if (text.empty()) return Error{ErrorCode::parse_error, where + ": empty field where a whole number is expected"};
    T value{};
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && ptr == text.data() + text.size() &&
                                                 (value < min || value > max)))
        return Error{ErrorCode::parse_error, where + ": " + excerpt(text) + " is out of range " + range};
    if (ec != std::errc() || ptr != text.data() + text.size())
        return Error{ErrorCode::parse_error, where + ": '" + excerpt(text) + "' is not a whole number in " + range};
    return value;
}
}  // namespace

Result<std::int64_t> parse_integer(std::string_view text, std::int64_t min, std::int64_t max, const std::string& where) {
    return parse_whole<std::int64_t>(text, min, max, where);
}

Result<std::uint64_t> parse_unsigned(std::string_view text, std::uint64_t max, const std::string& where) {
    return parse_whole<std::uint64_t>(text, 0, max, where);
}

Result<double> parse_number(std::string_view text, const std::string& where) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
    if (text == "NaN" || text == "nan" || text == "NAN") return std::numeric_limits<double>::quiet_NaN();
    if (text.empty()) return Error{ErrorCode::parse_error, where + ": empty field where a number is expected"};
    double value = 0;
    const char* first = text.data();
    if (*first == '+') ++first;
    auto [ptr, ec] = std::from_chars(first, text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size())
        return Error{ErrorCode::parse_error, where + ": '" + excerpt(text) + "' is not a number"};
    return value;
}

std::string escape(std::string_view field) {
    if (field.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(field);
    std::string out = "\"";
    for (char c : field) {
        if (c == '"') out.push_back('"');
        out.push_back(c);
    }
    out.push_back('"');
    return out;
}

void append_row(std::string& out, const std::vector<std::string>& fields) {
    for (std::size_t i = 0; i < fields.size(); ++i) {
        if (i) out.push_back(',');
        out += escape(fields[i]);
    }
    out.push_back('\n');
}

void append_number(std::string& out, double value) {
    if (std::isnan(value)) {
        out += "NaN";
    } else if (std::isinf(value)) {
        out += value > 0 ? "Inf" : "-Inf";
    } else {
        char buf[32];
        // Shortest representation that round-trips exactly (24 chars at most).
        const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, value);
        out.append(buf, static_cast<std::size_t>(ptr - buf));  // (buf, size): no replace() of a range
    }
}

namespace {
// "%.9g" of a sample in [1e-11, 1e9) by exact integer arithmetic, several times
// faster than std::to_chars with a precision (every recorded sample goes through
// here). value = M·2^e exactly, so value·10^k = M·10^k·2^e is rounded to a whole
// number of 9 digits without error, half to even as printf rounds. Returns what
// the text reads back as (digits / 10^k: both exact, one correctly rounded
// division, as from_chars gives it), or nullopt outside that range.
__extension__ using Wide = unsigned __int128;  // holds a 53-bit mantissa times 10^19

std::optional<double> append_sample_fast(std::string& out, double value) {
    const double magnitude = std::abs(value);
    if (!(magnitude >= 1e-11 && magnitude < 1e9)) return std::nullopt;
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    const Wide mantissa = (bits & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
    const int shift = 1075 - static_cast<int>((bits >> 52) & 0x7ff);  // value = mantissa / 2^shift
    static constexpr std::uint64_t kPow10[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000,
                                               1000000000, 10000000000, 100000000000, 1000000000000,
                                               10000000000000, 100000000000000, 1000000000000000,
                                               10000000000000000, 100000000000000000, 1000000000000000000,
                                               10000000000000000000u};
    // Decimal exponent of the leading digit, from the binary one: right or one
    // too small (log10 2 = 0.30103); the loop corrects it.
    int exponent = static_cast<int>(std::floor((52 - shift) * 0.30102999566398120));
    std::uint64_t digits = 0;
    for (int attempt = 0; attempt < 3; ++attempt) {
        const int k = 8 - exponent;
        if (k < 0 || k > 19) return std::nullopt;  // at the range's ends: to_chars decides
        const Wide scaled = mantissa * kPow10[k];
        const Wide whole = scaled >> shift;
        if (whole >= 1000000000) { ++exponent; continue; }
        if (whole < 100000000) { --exponent; continue; }
        const Wide rest = scaled - (whole << shift), half = Wide{1} << (shift - 1);
        digits = static_cast<std::uint64_t>(whole) + (rest > half || (rest == half && (whole & 1)) ? 1 : 0);
        break;
    }
    if (digits == 0) return std::nullopt;  // the estimate far off: cannot happen, but never guess
    const double read_back = static_cast<double>(digits) / static_cast<double>(kPow10[8 - exponent]);
    if (digits == 1000000000) digits = 100000000, ++exponent;  // 9.999999995 -> 10.0000000
    char text[9];
    for (int i = 8; i >= 0; --i, digits /= 10) text[i] = static_cast<char>('0' + digits % 10);
    int used = 9;
    while (used > 1 && text[used - 1] == '0') --used;  // %g drops trailing zeros
    char buf[24];  // "-0.000123456789" or "-1.23456789e-11" at most
    char* p = buf;
    if (value < 0) *p++ = '-';
    if (exponent < -4 || exponent >= 9) {  // d.dddde-XX
        *p++ = text[0];
        if (used > 1) *p++ = '.', p = std::copy(text + 1, text + used, p);
        const int e = std::abs(exponent);
        *p++ = 'e', *p++ = exponent < 0 ? '-' : '+';
        *p++ = static_cast<char>('0' + e / 10), *p++ = static_cast<char>('0' + e % 10);  // |exponent| <= 11 here
    } else if (exponent >= 0) {  // ddd.ddd
        p = std::copy(text, text + std::min(used, exponent + 1), p);
        for (int i = used; i < exponent + 1; ++i) *p++ = '0';
        if (used > exponent + 1) *p++ = '.', p = std::copy(text + exponent + 1, text + used, p);
    } else {  // 0.000ddd
        *p++ = '0', *p++ = '.';
        for (int i = 0; i < -exponent - 1; ++i) *p++ = '0';
        p = std::copy(text, text + used, p);
    }
    out.append(buf, static_cast<std::size_t>(p - buf));
    return value < 0 ? -read_back : read_back;
}
}  // namespace

double append_sample(std::string& out, double value) {
    if (!std::isfinite(value)) {
        append_number(out, value);
        return std::isnan(value) ? std::numeric_limits<double>::quiet_NaN() : value;  // as "NaN" parses
    }
    if (auto read_back = append_sample_fast(out, value)) return *read_back;
    const std::size_t from = out.size();
    char buf[32];
    // As "%.9g": 9 significant digits, trailing zeros dropped, an exponent of
    // at least two digits outside [1e-4, 1e9) (16 chars at most).
    const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, 9);
    out.append(buf, static_cast<std::size_t>(ptr - buf));
    return parse_number(std::string_view(out).substr(from), {}).value();
}

std::string format_number(double value) {
    std::string out;
    append_number(out, value);
    return out;
}

std::string format_sample(double value) {
    std::string out;
    append_sample(out, value);
    return out;
}

Result<KeyValues> read_key_values(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return KeyValues{};
    auto reader = Reader::open(file);
    if (!reader) return reader.error();
    auto key = reader->column("key");
    if (!key) return key.error();
    auto value = reader->column("value");
    if (!value) return value.error();
    KeyValues out;
    std::vector<std::string> fields;
    std::unordered_map<std::string, std::size_t> line_of;
    for (;;) {
        auto more = reader->next(fields);
        if (!more) return more.error();
        if (!*more) break;
        if (auto s = refuse_repeated_key(line_of, *reader, *key, fields[*key]); !s) return s.error();
        out.emplace_back(fields[*key], fields[*value]);
    }
    return out;
}

Status refuse_repeated_key(std::unordered_map<std::string, std::size_t>& seen, const Reader& reader,
                           std::size_t key_column, const std::string& key) {
    if (const auto [at, fresh] = seen.emplace(key, reader.line()); !fresh)
        return {ErrorCode::parse_error, reader.where(key_column) + ": '" + key + "' is given twice (first at line " +
                                            std::to_string(at->second) + "): keep one"};
    return {};
}

std::string format_key_values(const KeyValues& entries) {
    std::string out;
    append_row(out, {"key", "value"});
    for (const auto& [k, v] : entries) append_row(out, {k, v});
    return out;
}

}  // namespace rollsense::csv
