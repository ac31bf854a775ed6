#include <algorithm>

#include "rollsense/bagged_trees/tree.hpp"

namespace rollsense::bagged_trees {

std::string_view to_string(SplitCriterion c) noexcept {
    switch (c) {
        case SplitCriterion::gdi: return "gdi";
        case SplitCriterion::deviance: return "deviance";
        case SplitCriterion::twoing: return "twoing";
    }
    return "?";
}

Result<SplitCriterion> parse_split_criterion(std::string_view text) {
    if (text == "gdi") return SplitCriterion::gdi;
    if (text == "deviance") return SplitCriterion::deviance;
    if (text == "twoing") return SplitCriterion::twoing;
    return Error{ErrorCode::invalid_argument,
                 "unknown split criterion '" + std::string(text) + "' (expected gdi, deviance or twoing)"};
}

std::size_t Tree::leaves() const {
    return static_cast<std::size_t>(std::count_if(feature.begin(), feature.end(), [](auto f) { return f < 0; }));
}

}  // namespace rollsense::bagged_trees
