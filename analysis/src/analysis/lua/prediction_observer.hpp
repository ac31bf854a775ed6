// Who hears of each identification a script makes (clf:identify, clf:predict):
// the live view sets it to show the result after each trial. Called on the
// script's thread; must not block. Unset (the default), nothing is told.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rollsense/classifier.hpp"

struct lua_State;

namespace rollsense::runtime::lua_api {

using PredictionObserver =
    std::function<void(lua_State* L, const std::vector<std::string>& classes, const Prediction& prediction)>;
void set_prediction_observer(PredictionObserver observer);

}  // namespace rollsense::runtime::lua_api
