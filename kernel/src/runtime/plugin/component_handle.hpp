// The kernel's non-virtual wrapper around every plugin instance (NVI, as in ros2_control): it owns the lifecycle
// state machine, refuses illegal transitions, catches anything a plugin throws while the plugin's library is still
// loaded, and turns it into a typed error naming the instance and plugin.
#pragma once

#include <exception>
#include <memory>
#include <string>
#include <utility>

#include "rollsense/component.hpp"
#include "rollsense/log.hpp"
#include "rollsense/plugin.hpp"

namespace rollsense::runtime {

class LoadedLibrary;  // plugin_registry.hpp

class ComponentHandle {
public:
    ComponentHandle(std::string instance, std::shared_ptr<const LoadedLibrary> library, Component* component);
    ComponentHandle(const ComponentHandle&) = delete;
    ComponentHandle& operator=(const ComponentHandle&) = delete;
    virtual ~ComponentHandle();

    const std::string& instance() const { return instance_; }
    const std::string& plugin_name() const;
    std::string plugin_build() const;  // "sim 1.0.0 (/…/librollsense_sim.so)": a rebuilt or moved plugin is told apart
    LifecycleState state() const { return state_; }
    // The error that moved the component to `error` (empty otherwise).
    const Status& last_error() const { return last_error_; }

    Status configure(const ParamSet& params, const PluginContext& context);
    Status activate();
    Status deactivate();
    Status cleanup();
    // error → unconfigured, through the plugin's on_recover().
    Status recover();
    Result<ValueMap> invoke(const std::string& verb, const ValueMap& args);

    // Run a plugin call: exceptions become plugin_error, a failing Status is prefixed with the instance name; either
    // moves the component to `error` unless the failure is the caller's: `keeps_state` (e.g. a command refused as out
    // of range), or not_found, a request for what does not exist (a trial's unknown object).
    template <class F>
    Status call(const char* what, F&& fn, bool keeps_state = false) {
        // Initialised by the call itself, not assigned over: several calls per control period.
        Status s = [&]() -> Status {
            try {
                return fn();
            } catch (const StatusError& e) {
                return e.status();
            } catch (const std::exception& e) {
                return {ErrorCode::plugin_error, std::string("threw an exception in ") + what + ": " + e.what()};
            } catch (...) {
                return {ErrorCode::plugin_error, std::string("threw a non-standard exception in ") + what};
            }
        }();
        if (s.ok()) return s;
        s = std::move(s).with_context(describe());
        if (!keeps_state && s.code() != ErrorCode::not_found) enter_error(s);
        return s;
    }

    // Refuse a runtime call unless active.
    Status require_active(const char* what) const;
    std::string describe() const;  // "device 'tactile' (plugin 'sim')"

protected:
    Component* component_;

private:
    Status transition(const char* what, LifecycleState from, LifecycleState to, Status (Component::*hook)());
    void enter_error(const Status& why);

    std::string instance_;
    std::shared_ptr<const LoadedLibrary> library_;  // keeps the code of component_ mapped
    LifecycleState state_ = LifecycleState::unconfigured;
    Status last_error_;
};

template <class T>
class Handle : public ComponentHandle {
public:
    Handle(std::string instance, std::shared_ptr<const LoadedLibrary> library, T* plugin)
        : ComponentHandle(std::move(instance), std::move(library), plugin), plugin_(plugin) {}
    T& plugin() { return *plugin_; }
    const T& plugin() const { return *plugin_; }

private:
    T* plugin_;
};

using SensorHandle = Handle<Sensor>;
using ActuatorHandle = Handle<Actuator>;
using ClassifierHandle = Handle<Classifier>;

}  // namespace rollsense::runtime
