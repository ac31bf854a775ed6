// Where a Lua file writes the keys of its table constructors, read from its
// text. Lua keeps no line for a table's fields, so the profile loader asks this
// scan for the file:line its errors name ("sim.lua:7: sample_rate_hz = -5: ...").
// The scan knows Lua's tokens (comments, strings, long brackets), not its
// statements: a key path is that of the constructors' nesting, counted from the
// outermost one. What it cannot be sure of gives no line: a path written twice
// in the file, one it does not write, and a literal that is no longer what the
// file wrote there (set later by an assignment or a --set). A value written as
// an expression cannot be compared, and is placed where it is written.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "rollsense/params.hpp"

namespace rollsense {

class TableSource {
public:
    TableSource() = default;
    // Reads and scans `file`; one that cannot be read gives no lines.
    static TableSource scan(const std::filesystem::path& file);
    // Scans `text` as the content of `file` (which only names it).
    TableSource(std::string file, std::string_view text);

    // "FILE:LINE" where `path` ("devices.tactile.params.joint", list entries
    // by 1-based index: "record_joints.2") is written; "FILE" when it is
    // written twice. `now` (may be null) is the value the table holds. "" when
    // the value did not come from this file's text: the path is not written
    // here (added later, or reached through a name), or the file wrote another
    // literal there (a list: other entries).
    std::string where(const std::string& path, const ParamValue* now) const;

private:
    struct Site {
        int line = 0;       // 0: written more than once, unknown
        char kind = 0;      // the value as written: 'n' number, 's' string, 'b' true/false, 0 anything else
        std::string text;   // its text ('s': without the quotes)
    };
    std::string file_;
    std::map<std::string, Site> sites_;
};

// The entry of `sites` (path → "FILE:LINE") for `path` or its nearest parent that has one; `fallback` when none
// or when that entry is "" (a value not from the file that wrote its table: see where()).
std::string nearest_site(const std::map<std::string, std::string>& sites, std::string path, const std::string& fallback);

// The key of `keys` that `message` names first as a whole word ("cell_angles is empty": cell_angles), or null.
const std::string* key_named_in(std::string_view message, const std::map<std::string, ParamValue>& keys);

}  // namespace rollsense
