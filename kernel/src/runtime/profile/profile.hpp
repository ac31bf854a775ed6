// Robot profiles: Lua files in share/profiles/ that say which plugin drives which device, with what parameters, what
// the joint limits are and how the run is clocked; every key, its default and its checks: docs/profiles.md. A profile
// is configuration only (Cartographer-style): it runs in an empty sandbox with `include` and `setting`, and every key
// must be one the kernel knows, so a typo is an error naming the file:line and the key instead of a silent default.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rollsense/params.hpp"
#include "rollsense/status.hpp"
#include "rollsense/table_source.hpp"

namespace rollsense::runtime {

struct DeviceSpec {
    std::string name;
    std::string plugin;
    std::map<std::string, ParamValue> params;
};

struct JointLimit {
    std::string name;
    double min = 0, max = 0;
    double max_velocity = 0;  // unit/s, 0 = no profile limit
    double max_current = 0;   // mA, 0 = no profile limit
    bool safe_torque_off = false;  // safe state: false = hold position, true = torque off
};

struct ControllerSpec {
    std::string name;
    std::map<std::string, ParamValue> params;
};

struct GpioLine {
    std::string chip;
    unsigned line = 0;
    bool active_low = false;
    double pulse_ms = 5.0;  // trigger output only
};

struct Profile {
    std::string name;
    std::filesystem::path path;
    std::string description;
    bool virtual_clock = true;
    double sample_rate_hz = 31.1;
    double control_rate_hz = 100.0;
    std::vector<std::filesystem::path> plugin_path;
    std::vector<DeviceSpec> devices;
    std::vector<JointLimit> joints;
    std::vector<std::string> record_joints;
    std::vector<std::string> identification_channels;  // into dataset-info.csv: the 3 the analysis reads
    std::vector<ControllerSpec> controllers;
    std::optional<GpioLine> estop;
    std::optional<GpioLine> trigger;
    std::map<std::string, std::string> sites;  // "joints.palm.min" → ".../etroll-joints.lua:9": where the files write it

    // "FILE:LINE" for an error about `key`: where it, or its nearest written parent, is written (else the file).
    std::string site(const std::string& key) const { return nearest_site(sites, key, path.string()); }
    std::string at(const std::string& key) const { return site(key) + ": " + key; }  // "FILE:LINE: joints.palm.min"
};

// Command-line settings (--set key=value). One namespace rule (docs/scripting.md, "Settings"): a profile entry
// (sample_rate_hz) or a dotted path under one (devices., joints., ...) overrides that part of the profile, so a plugin
// parameter is devices.NAME.params.KEY; every other key is a script setting: plain for the script (and a profile's
// `setting`), MODULE.KEY for a Lua module (etroll.clamp_current).
class Settings {
public:
    Status add(const std::string& key_equals_value);
    void set(const std::string& key, ParamValue value) { values_[key] = std::move(value); }
    const ParamValue* find(const std::string& key) const;  // marks the key as used
    const std::map<std::string, ParamValue>& values() const { return values_; }
    std::vector<std::string> unused() const;
    void mark_used(const std::string& key) const { used_.insert(key); }
    bool used(const std::string& key) const { return used_.count(key) > 0; }

    // Declared settings (rs.settings): once a namespace ("" for plain keys, "etroll" for etroll.*) declares its
    // settings, reading an undeclared key of it is an error. The declared default stands in for a missing --set.
    void declare(const std::string& key, ParamValue fallback) { declared_[key] = std::move(fallback); }
    const std::map<std::string, ParamValue>& declared() const { return declared_; }
    bool namespace_declared(const std::string& key) const;

private:
    std::map<std::string, ParamValue> values_;
    std::map<std::string, ParamValue> declared_;
    mutable std::set<std::string> used_;
};

// "etroll" for etroll.clamp_current, "" for a plain key.
std::string setting_namespace(const std::string& key);
// True for a profile entry (sample_rate_hz) or a path under one (devices.tactile.params.x).
bool is_profile_path(const std::string& key);

// <share>/profiles/<name>.lua for a name; a path (with '/', or ending in .lua) as given.
std::filesystem::path resolve_profile_path(const std::string& name_or_path, const std::filesystem::path& share_dir);

// A profile whose content is wrong is a bad input file (exit 3), like one that does not parse; wrong by a --set of it
// (the message names its key, or its leaf quoted: 'kernel_fwhm'), a bad command line (exit 2). Other errors as they are.
Status profile_refusal(const Status& s, const Settings& settings);

struct SandboxLimits;
// A profile is Lua: it runs under the scripts' memory cap and no-wait limit (`limits`; defaults when not given), so a
// looping or allocating profile ends with an error naming it.
Result<Profile> load_profile(const std::string& name_or_path, const std::filesystem::path& share_dir,
                             const Settings& settings);
Result<Profile> load_profile(const std::string& name_or_path, const std::filesystem::path& share_dir,
                             const Settings& settings, const SandboxLimits& limits);

}  // namespace rollsense::runtime
