// Joint-level controllers that run in C++ on the control loop, once per control period, between reading the actuators
// and writing them (for instance the palm-parallel controller). Lua only enables and disables them.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rollsense/params.hpp"
#include "rollsense/types.hpp"
#include "runtime/profile/profile.hpp"

namespace rollsense::runtime {

// What a controller may see and do. Commands go through the same limit checks as a script's commands.
class JointAccess {
public:
    virtual ~JointAccess() = default;
    virtual const JointState* state(const std::string& joint) const = 0;
    virtual const JointInfo* info(const std::string& joint) const = 0;
    virtual const JointCommand* command(const std::string& joint) const = 0;
    // The limits the kernel enforces on the joint (a controller clamps its goals into them).
    virtual const JointLimit* limit(const std::string& joint) const = 0;
    virtual Status set_command(const std::string& joint, const JointCommand& command) = 0;
};

class Controller {
public:
    virtual ~Controller() = default;
    // Called when a script enables the controller; check joints exist here.
    virtual Status enable(double time, JointAccess& joints) = 0;
    virtual void disable(double time, JointAccess& joints) { (void)time, (void)joints; }
    virtual Status update(double time, double dt, JointAccess& joints) = 0;
    // A value a script can read back (e.g. tracking error); empty by default.
    virtual std::map<std::string, double> telemetry() const { return {}; }
};

struct ControllerType {
    std::string name;
    std::string description;
    ParamSchema schema;
    std::function<std::unique_ptr<Controller>(const ParamSet&)> create;
};

// Built-in controller types register here at static-initialisation time.
struct ControllerRegistration {
    explicit ControllerRegistration(ControllerType type);
};
const ControllerType* find_controller_type(const std::string& name);
std::vector<std::string> controller_type_names();

}  // namespace rollsense::runtime
