#include "runtime/plugin/component_handle.hpp"

#include "runtime/plugin/plugin_registry.hpp"

namespace rollsense::runtime {

ComponentHandle::ComponentHandle(std::string instance, std::shared_ptr<const LoadedLibrary> library,
                                 Component* component)
    : component_(component), instance_(std::move(instance)), library_(std::move(library)) {}

ComponentHandle::~ComponentHandle() {
    // Destroy through the plugin's own destroy() while its library is mapped;
    // library_ is released after this body runs.
    if (component_ && library_) library_->manifest().destroy(component_);
}

const std::string& ComponentHandle::plugin_name() const { return library_->name(); }
std::string ComponentHandle::plugin_build() const {
    return library_->name() + " " + library_->manifest().version + " (" + library_->path().string() + ")";
}

std::string ComponentHandle::describe() const {  // a classifier is no device of the profile (user review)
    if (library_->manifest().kind == PluginKind::classifier) return "classifier plugin '" + plugin_name() + "'";
    return "device '" + instance_ + "' (plugin '" + plugin_name() + "')";
}

// Not logged as an error here: the failing Status goes back to the caller,
// and the run prints it once, at the top, with the script's place.
void ComponentHandle::enter_error(const Status& why) {
    state_ = LifecycleState::error;
    last_error_ = why;
    log_debug(instance_, why.message() + " [now in error state; recover() or reconfigure]");
}

// In the error state the fault is named by its kind only: its text was
// reported when it happened, and repeating it in every refusal prints it twice.
Status ComponentHandle::require_active(const char* what) const {
    if (state_ == LifecycleState::active) return {};
    return {ErrorCode::state_error, describe() + ": " + what + " needs the active state, it is " +
                                        std::string(to_string(state_)) +
                                        (state_ == LifecycleState::error
                                             ? " (after its fault: " + std::string(to_string(last_error_.code())) + ")"
                                             : "")};
}

Status ComponentHandle::transition(const char* what, LifecycleState from, LifecycleState to,
                                   Status (Component::*hook)()) {
    if (state_ != from)
        return {ErrorCode::state_error, describe() + ": cannot " + what + " from state " +
                                            std::string(to_string(state_)) + " (needs " +
                                            std::string(to_string(from)) + ")"};
    // c, not this->component_: gcc -O2 -fsanitize=address warned (falsely) -Wmaybe-uninitialized on the latter.
    auto s = call(what, [&, c = component_] { return (c->*hook)(); });
    if (s.ok()) state_ = to;
    return s;
}

Status ComponentHandle::configure(const ParamSet& params, const PluginContext& context) {
    if (state_ != LifecycleState::unconfigured)
        return {ErrorCode::state_error,
                describe() + ": cannot configure from state " + std::string(to_string(state_)) + " (needs unconfigured)"};
    auto s = call("configure", [&] { return component_->on_configure(params, context); });
    if (s.ok()) state_ = LifecycleState::inactive;
    return s;
}

Status ComponentHandle::activate() {
    return transition("activate", LifecycleState::inactive, LifecycleState::active, &Component::on_activate);
}
Status ComponentHandle::deactivate() {
    return transition("deactivate", LifecycleState::active, LifecycleState::inactive, &Component::on_deactivate);
}
Status ComponentHandle::cleanup() {
    return transition("cleanup", LifecycleState::inactive, LifecycleState::unconfigured, &Component::on_cleanup);
}

Status ComponentHandle::recover() {
    if (state_ != LifecycleState::error)
        return {ErrorCode::state_error, describe() + ": recover is only for the error state, it is " +
                                            std::string(to_string(state_))};
    auto s = call("recover", [&] { return component_->on_recover(); });
    if (s.ok()) {
        state_ = LifecycleState::unconfigured;
        last_error_ = {};
    }
    return s;
}

Result<ValueMap> ComponentHandle::invoke(const std::string& verb, const ValueMap& args) {
    Result<ValueMap> out = ValueMap{};
    auto s = call(
        "invoke", [&] {
            out = component_->invoke(verb, args);
            return out.status();
        },
        /*keeps_state=*/true);
    if (!s.ok()) return s.error();
    return out;
}

}  // namespace rollsense::runtime
