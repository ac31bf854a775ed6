#include "runtime/plugin/plugin_registry.hpp"

#include "rollsense/log.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include <dlfcn.h>
#include <elf.h>

#include <boost/dll/runtime_symbol_info.hpp>

namespace rollsense::runtime {
namespace fs = std::filesystem;

namespace {
// Plugin and parameter names: profiles, --set and --classifier entries and model files spell them.
constexpr std::string_view kNameCharacters = "abcdefghijklmnopqrstuvwxyz0123456789_";

std::string article(PluginKind kind) {
    const std::string name(to_string(kind));
    return (kind == PluginKind::actuator ? "an " : "a ") + name;
}

// dlopen maps a library's segments straight from the file: in a truncated one they reach past its end, and the first
// touch of them is a SIGBUS no error return reports. So first: does the file hold every byte its ELF64 headers point
// at? Empty if so, or if it is no ELF64 file (dlopen says why then).
std::string truncation(const fs::path& file) {
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    const auto size = static_cast<std::uintmax_t>(in.tellg());
    Elf64_Ehdr h{};
    Elf64_Phdr p{};
    if (!in.seekg(0).read(reinterpret_cast<char*>(&h), sizeof h) || std::memcmp(h.e_ident, ELFMAG, SELFMAG) != 0 ||
        h.e_ident[EI_CLASS] != ELFCLASS64)
        return {};
    std::uintmax_t need = std::max(h.e_phoff + std::uintmax_t{h.e_phnum} * h.e_phentsize,
                                   h.e_shoff + std::uintmax_t{h.e_shnum} * h.e_shentsize);
    in.seekg(static_cast<std::streamoff>(h.e_phoff));
    for (int i = 0; i < h.e_phnum && h.e_phentsize == sizeof p && in.read(reinterpret_cast<char*>(&p), sizeof p); ++i)
        if (p.p_type == PT_LOAD) need = std::max<std::uintmax_t>(need, p.p_offset + p.p_filesz);
    if (size >= need) return {};
    return "truncated: " + std::to_string(size) + " bytes, its headers need " + std::to_string(need) +
           " (a damaged or half-copied file: rebuild or reinstall it, or remove it from the search path)";
}
}  // namespace

PluginRegistry::PluginRegistry(std::vector<fs::path> search_path) : search_path_(std::move(search_path)) {}

std::vector<fs::path> PluginRegistry::default_search_path(const std::vector<fs::path>& extra) {
    std::vector<fs::path> out = extra;
    if (const char* env = std::getenv("ROLLSENSE_PLUGIN_PATH")) {
        std::istringstream folders(env);
        for (std::string folder; std::getline(folders, folder, ':');)
            if (!folder.empty()) out.emplace_back(folder);
    }
    // <prefix>/bin/rollsense → <prefix>/lib/rollsense/plugins (same layout in the build tree).
    const auto prefix = fs::path(boost::dll::program_location().string()).parent_path().parent_path();
    out.push_back(prefix / ROLLSENSE_PLUGIN_INSTALL_SUBDIR);
    out.push_back(prefix / "lib" / "rollsense" / "plugins");
    // Remove duplicates (the two above when the install layout is the build tree's; "dir/" and "dir"), keep order.
    std::vector<fs::path> unique;
    for (auto& p : out) {
        const auto norm = p.lexically_normal().has_filename() ? p.lexically_normal() : p.lexically_normal().parent_path();
        if (std::find(unique.begin(), unique.end(), norm) == unique.end()) unique.push_back(norm);
    }
    return unique;
}

PluginCandidate PluginRegistry::load_file(const fs::path& file) {
    PluginCandidate c;
    c.path = file;
    const auto fail = [&c](std::string why) { c.failure = std::move(why); return c; };
    if (auto cut = truncation(file); !cut.empty()) return fail(cut);
    boost::dll::shared_library lib;
    boost::dll::fs::error_code ec;  // not the throwing load: its what() adds an errno text unrelated to dlerror()'s
    // Every symbol bound now: one missing is this file's failure here, not a process killed mid-run (review).
    try {
        lib.load(file.string(), boost::dll::load_mode::rtld_now | boost::dll::load_mode::rtld_local, ec);
    } catch (...) {  // a static initialiser threw: the unwind left the loader's lock held, so any thread may hang now
        log_error("plugins", file.string() + ": its static initialisation threw an exception, which leaves the dynamic "
                             "loader locked: the process stops here (fix the plugin or remove it from the search path)");
        std::fflush(stderr);
        std::_Exit(3);
    }
    if (ec) {  // dlopen's own reason; about a library this one needs, it names that library, not this file
        const char* why = ::dlerror();
        return fail("cannot be loaded: " + (why ? std::string(why) : ec.message()) +
                    (why && !std::string_view(why).starts_with(file.string())
                         ? " (a library it needs: `ldd " + file.string() + "` shows which is missing; install it "
                           "or add its folder to LD_LIBRARY_PATH)"
                         : " (rebuild or reinstall it, or remove it from the search path)"));
    }
    if (!lib.has(kPluginManifestSymbol))
        return fail(std::string("not a rollsense plugin: missing symbol '") + kPluginManifestSymbol +
                    "' (a plugin defines it with ROLLSENSE_PLUGIN(...))");
    const PluginManifest* m = nullptr;
    try {
        m = lib.get_alias<PluginManifestFn>(kPluginManifestSymbol)();
    } catch (const std::exception& e) {
        return fail(std::string("its manifest function failed: ") + e.what());
    } catch (...) {
        return fail("its manifest function threw a value that is not a std::exception");
    }
    if (!m || m->magic != kPluginMagic)
        return fail("not a rollsense plugin: the manifest symbol does not point at a rollsense manifest");
    if (m->abi_version != kPluginAbiVersion)
        return fail("ABI mismatch: built for plugin ABI " + std::to_string(m->abi_version) + ", this rollsense has " +
                    std::to_string(kPluginAbiVersion) + " (rebuild the plugin against this SDK)");
    if (!m->compiler_tag || std::strcmp(m->compiler_tag, ROLLSENSE_COMPILER_TAG) != 0)
        return fail(std::string("ABI mismatch: built with compiler '") + (m->compiler_tag ? m->compiler_tag : "?") +
                    "', this rollsense with '" + ROLLSENSE_COMPILER_TAG +
                    "' (rebuild the plugin with the same compiler, and without -D_GLIBCXX_DEBUG)");
    const bool factory_ok = (m->kind == PluginKind::sensor && m->create_sensor) ||
                            (m->kind == PluginKind::actuator && m->create_actuator) ||
                            (m->kind == PluginKind::classifier && m->create_classifier);
    if (!m->name || !factory_ok || !m->destroy || !m->schema)
        return fail("malformed manifest: missing name, factory for its kind, destroy or schema");
    if (!*m->name || std::string_view(m->name).find_first_not_of(kNameCharacters) != std::string_view::npos)
        return fail("its name '" + std::string(m->name) + "' is not made of a-z, 0-9 and _ (a model file, a profile and --classifier name it): rename it in ROLLSENSE_PLUGIN(...)");
    c.library = std::make_shared<LoadedLibrary>(std::move(lib), m, file);
    return c;
}

const std::vector<PluginCandidate>& PluginRegistry::scan() {
    if (scanned_) return candidates_;
    scanned_ = true;
    std::map<std::string, fs::path> seen;
    for (const auto& dir : search_path_) {
        std::error_code ec;
        if (!fs::is_directory(dir, ec)) continue;
        std::vector<fs::path> files;
        for (const auto& entry : fs::directory_iterator(dir, ec))
            if (entry.path().extension() == ".so" || entry.path().filename().string().find(".so.") != std::string::npos)
                files.push_back(entry.path());
        std::sort(files.begin(), files.end());
        for (const auto& f : files) {
            auto c = load_file(f);
            if (auto [it, first] = c.library ? seen.emplace(c.library->name(), f) : std::pair(seen.end(), true); !first) {
                c.overridden = it->second.parent_path() != f.parent_path();  // --plugin-path over an installed copy
                c.failure = "shadowed: a plugin named '" + c.library->name() + "' was already found at " +
                            it->second.string() + (c.overridden ? ", earlier in the search path" : ", in the same folder");
                c.library.reset();
            }
            candidates_.push_back(std::move(c));
        }
    }
    return candidates_;
}

Result<std::shared_ptr<const LoadedLibrary>> PluginRegistry::find(const std::string& name, PluginKind kind) {
    scan();
    for (auto& c : candidates_) {
        if (c.library && c.library->name() == name) {
            if (c.library->manifest().kind != kind)
                return Error{ErrorCode::not_found, "plugin '" + name + "' at " + c.path.string() + " is " +
                                                       article(c.library->manifest().kind) + " plugin, not " +
                                                       article(kind)};
            // Said once (first find()): a file of this one's name earlier in the search path that failed to load, and
            // another file of the same folder naming the same plugin (a stale build; plugin review: used silently).
            for (auto& d : candidates_)
                if (!d.library && !d.warned && ((&d < &c && d.path.filename() == c.path.filename()) ||
                                                (!d.overridden && d.failure.starts_with("shadowed: a plugin named '" + name + "'")))) {
                    d.warned = true;
                    log_warning("plugins", d.path.string() + " is not used: " + d.failure + ". Plugin '" + name +
                                               "' comes from " + c.path.string() + " instead (see `rollsense plugins`)");
                }
            return c.library;
        }
    }
    std::string msg = "no " + std::string(to_string(kind)) + " plugin named '" + name + "'";
    // Its own file, found but refused (another compiler, a missing library): that first (review: it read as absent).
    for (const auto& c : candidates_)
        if (!c.library && c.is_plugin(name))
            msg += " loads: " + c.path.string() + " is not used: " + c.failure;
    msg += ". Searched:";
    for (const auto& d : search_path_) msg += "\n  " + d.string() + (fs::is_directory(d) ? "" : " (no such folder)");
    msg += candidates_.empty() ? "\nNo plugin files were found." : "\nFound:";
    for (const auto& c : candidates_)
        msg += "\n  " + c.path.string() + ": " + (c.library ? "plugin '" + c.library->name() + "'" : c.failure);
    msg += "\nAdd a folder with --plugin-path or the profile's plugin_path; `rollsense plugins` lists what loads.";
    return Error{ErrorCode::not_found, msg};
}

namespace {
// A schema's own mistakes, which loading does not catch: a parameter declared twice, or a default its own range or
// choices refuse (used silently, while the same value in a profile is refused). Empty if none.
std::string schema_problem(const ParamSchema& schema) {
    ParamSchema with_default;
    std::map<std::string, ParamValue> defaults;
    for (const auto& p : schema) {
        if (std::ranges::count(schema, p.name, &ParamSpec::name) > 1) return "parameter '" + p.name + "' is declared twice";
        if (p.name.empty() || p.name.find_first_not_of(kNameCharacters) != std::string::npos)
            return "parameter '" + p.name + "': a name is a-z, 0-9 and _ (--set and --classifier entries spell it)";
        if (p.min && p.max && *p.min > *p.max) return "parameter '" + p.name + "': its range [min, max] is empty";
        if (p.default_value) with_default.push_back(p), defaults[p.name] = *p.default_value;
    }
    const auto checked = validate_params(with_default, defaults, "a default its own declaration refuses");
    return checked ? std::string() : checked.error().message;
}
}  // namespace

// Checked wherever it is used (review: `plugins --check` refused a schema that a run then used).
Result<ParamSchema> PluginRegistry::schema_of(const LoadedLibrary& library) {
    try {
        ParamSchema schema = library.manifest().schema();
        if (const auto problem = schema_problem(schema); !problem.empty())
            return Error{ErrorCode::plugin_error, "plugin '" + library.name() + "': its schema is wrong: " + problem +
                                                      " (fix the plugin's schema function)"};
        return schema;
    } catch (const std::exception& e) {
        return Error{ErrorCode::plugin_error, "plugin '" + library.name() + "': schema() threw: " + e.what()};
    } catch (...) {
        return Error{ErrorCode::plugin_error, "plugin '" + library.name() + "': schema() threw a non-std::exception"};
    }
}

namespace {
template <class T, class Create>
Result<std::unique_ptr<Handle<T>>> create(PluginRegistry& reg, const std::string& plugin, const std::string& instance,
                                          PluginKind kind, Create factory) {
    auto lib = reg.find(plugin, kind);
    if (!lib) return lib.error();
    T* object = nullptr;
    try {
        object = ((*lib)->manifest().*factory)();
    } catch (const std::exception& e) {
        return Error{ErrorCode::plugin_error, "plugin '" + plugin + "': constructor threw: " + e.what()};
    } catch (...) {  // review: `throw 42` ended the process (std::terminate)
        return Error{ErrorCode::plugin_error, "plugin '" + plugin + "': constructor threw a non-std::exception"};
    }
    if (!object) return Error{ErrorCode::plugin_error, "plugin '" + plugin + "': factory returned nothing"};
    return std::make_unique<Handle<T>>(instance, *lib, object);
}
}  // namespace

Result<std::unique_ptr<SensorHandle>> PluginRegistry::create_sensor(const std::string& plugin,
                                                                    const std::string& instance) {
    return create<Sensor>(*this, plugin, instance, PluginKind::sensor, &PluginManifest::create_sensor);
}
Result<std::unique_ptr<ActuatorHandle>> PluginRegistry::create_actuator(const std::string& plugin,
                                                                        const std::string& instance) {
    return create<Actuator>(*this, plugin, instance, PluginKind::actuator, &PluginManifest::create_actuator);
}
Result<std::unique_ptr<ClassifierHandle>> PluginRegistry::create_classifier(const std::string& plugin,
                                                                            const std::string& instance) {
    return create<Classifier>(*this, plugin, instance, PluginKind::classifier, &PluginManifest::create_classifier);
}

}  // namespace rollsense::runtime
