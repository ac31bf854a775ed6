// Finds, loads and describes plugin libraries (Boost.DLL).
//
// Search order: paths given on the command line, then the profile's plugin_path, then $ROLLSENSE_PLUGIN_PATH (colon
// separated), then the install location next to the program (<prefix>/lib/rollsense/plugins). Every `*.so` in those
// folders is a candidate; `rollsense plugins` shows each candidate with its manifest or the exact reason it was not
// loaded.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <boost/dll/shared_library.hpp>

#include "rollsense/plugin.hpp"
#include "runtime/plugin/component_handle.hpp"

namespace rollsense::runtime {

// A loaded plugin library and its manifest. Instances hold a shared_ptr to it,
// so the code stays mapped as long as any object made by it lives.
class LoadedLibrary {
public:
    LoadedLibrary(boost::dll::shared_library library, const PluginManifest* manifest, std::filesystem::path path)
        : library_(std::move(library)), manifest_(manifest), path_(std::move(path)) {}
    const PluginManifest& manifest() const { return *manifest_; }
    const std::string& name() const { return name_ = manifest_->name; }
    const std::filesystem::path& path() const { return path_; }

private:
    boost::dll::shared_library library_;
    const PluginManifest* manifest_;
    std::filesystem::path path_;
    mutable std::string name_;
};

struct PluginCandidate {
    std::filesystem::path path;
    std::shared_ptr<const LoadedLibrary> library;  // null when it failed to load
    std::string failure;                           // why it is not usable
    bool overridden = false;                       // a namesake in a folder earlier in the search path is used
    bool warned = false;                           // find() said once that a namesake runs instead
    bool is_plugin(const std::string& n) const {  // loaded as plugin n, or its file (librollsense_<n>.so) refused
        return library ? library->name() == n : path.filename().string().starts_with("librollsense_" + n + ".so");
    }
};

class PluginRegistry {
public:
    explicit PluginRegistry(std::vector<std::filesystem::path> search_path);

    // The default search path for this program: extra (command line, profile),
    // then $ROLLSENSE_PLUGIN_PATH, then the install location.
    static std::vector<std::filesystem::path> default_search_path(const std::vector<std::filesystem::path>& extra);

    const std::vector<std::filesystem::path>& search_path() const { return search_path_; }
    // Every candidate file, loaded or not (cached after the first scan).
    const std::vector<PluginCandidate>& scan();
    // Load one library file, with the reason on failure (also used by scan()).
    static PluginCandidate load_file(const std::filesystem::path& file);

    Result<std::shared_ptr<const LoadedLibrary>> find(const std::string& name, PluginKind kind);

    Result<std::unique_ptr<SensorHandle>> create_sensor(const std::string& plugin, const std::string& instance);
    Result<std::unique_ptr<ActuatorHandle>> create_actuator(const std::string& plugin, const std::string& instance);
    Result<std::unique_ptr<ClassifierHandle>> create_classifier(const std::string& plugin,
                                                                const std::string& instance);

    // The plugin's parameter schema (calls into the library, exceptions caught).
    static Result<ParamSchema> schema_of(const LoadedLibrary& library);

private:
    std::vector<std::filesystem::path> search_path_;
    std::vector<PluginCandidate> candidates_;
    bool scanned_ = false;
};

}  // namespace rollsense::runtime
