// The sim sensor's parameters: every physical setting with its unit and a
// one-line doc (shown by `rollsense plugins`), and the mapping to SimParameters.
#pragma once

#include <string>

#include "rollsense/params.hpp"
#include "sim_model.hpp"

namespace rollsense::sim {

ParamSchema sim_schema();

struct SimSettings {
    SimParameters physics;
    std::string catalogue;       // path, relative to the share folder unless absolute
    std::string sensing_joint;
    std::string pushing_joint;
    std::string palm_joint;
};

// ParamSet validated against sim_schema() → settings.
SimSettings sim_settings_from(const ParamSet& params);

}  // namespace rollsense::sim
