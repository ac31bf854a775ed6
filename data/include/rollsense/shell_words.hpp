// Command lines as text a POSIX shell reads back: how run-info.csv records the command that made a dataset, and how
// the commands rollsense prints for a user to paste are quoted.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rollsense {

// `text` as one shell word: unchanged when it is plain (letters, digits, _-./=,:+@%), else in single quotes.
std::string shell_quote(std::string_view text);

// Each word shell-quoted, joined by spaces.
std::string shell_join(const std::vector<std::string>& words);

// The words of a command line as shell_join writes it: single quotes, double quotes and backslashes are read as a
// shell reads them; no expansion. An unquoted line (as run-info.csv recorded it before quoting) splits at spaces
// unless it holds a quote or a backslash, which are then read as quoting.
std::vector<std::string> shell_split(std::string_view line);

}  // namespace rollsense
