// Whether a run ended inside its analysis: `rollsense run` tells a failed
// analysis (its trials are all on disk; what helps is to analyse them again,
// e.g. with other options) from a failed recording (what helps is --resume).
#pragma once

#include <filesystem>
#include <optional>

namespace rollsense::runtime::lua_api {

// The dataset of an rs.analyse that started in this process's latest session
// and did not return: it raised an error, or Ctrl-C stopped it. None when no
// rs.analyse started or every one returned. Read after the session has ended.
std::optional<std::filesystem::path> unfinished_analysis();

}  // namespace rollsense::runtime::lua_api
