// The settings reflection table: every settings struct lists its fields once, in visit(), with
// the key, description, unit, range and what a change costs. JSON, validation, `--set`,
// `--list-settings`, the ImGui panels, diffing and the tests all walk that one list (reflect.h).
#pragma once

#include <glm/vec3.hpp>

#include <array>
#include <concepts>
#include <memory>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gi {

// What the host must do when a field changes. Values are bits so a diff can OR them.
enum class Cost : uint8_t {
    Uniform = 1,     // upload a uniform next frame
    Reallocate = 2,  // resize or recreate GPU resources
    Recompile = 4,   // rebuild a shader variant
    ReloadScene = 8  // reload scene files and rebuild the GPU scene
};
inline Cost operator|(Cost a, Cost b) { return Cost(uint8_t(a) | uint8_t(b)); }
inline bool any(Cost c, Cost bit) { return (uint8_t(c) & uint8_t(bit)) != 0; }
const char* costName(Cost c);
// A settings key as words for labels: "shadowMapSize" -> "shadow map size"; acronyms stay
// ("memoryBudgetMB" -> "memory budget MB", "SHOrder" -> "SH order", "fovY" -> "fov Y").
std::string readableKey(std::string_view key);

inline constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// Metadata of one field, given once in the struct's visit().
struct FieldMeta {
    const char* key;          // JSON key, equal to the C++ field name
    const char* description;  // one sentence for tooltips and --list-settings
    const char* unit = "";    // "deg", "px", "EV", "" for unitless
    double min = -kNoLimit;   // inclusive range for numbers (each component of a vec3)
    double max = kNoLimit;
    Cost cost = Cost::Uniform;
    double step = 0.0;        // UI drag speed; 0 picks one from the range
    bool developer = false;   // a setting one debugs rather than tunes (forDevelopers)
};

// Marks a field as one a developer debugs (biases, sample counts, budgets, test thresholds)
// rather than one an artist tunes: the editor shows it under its section's "developer" node,
// --list-settings and settingInfo() say so. JSON, --set and validation treat both alike.
constexpr FieldMeta forDevelopers(FieldMeta m) {
    m.developer = true;
    return m;
}

// Enums reflect through a name table: specialise EnumNames<E> with a `values` array of
// {value, "name"} pairs. JSON and --set use the names.
template <class E>
struct EnumNames;

template <class E>
concept ReflectedEnum = std::is_enum_v<E> && requires { EnumNames<E>::values; };

template <ReflectedEnum E>
const char* enumName(E value) {
    for (const auto& [v, name] : EnumNames<E>::values)
        if (v == value) return name;
    return "?";
}

// A string chosen from a list known at run time (the registered techniques): T has `name` and
// a static choices().
template <class T>
concept ChoiceString = requires(T t) {
    { T::choices() } -> std::convertible_to<std::vector<std::string>>;
    { t.name } -> std::convertible_to<std::string>;
};

template <class S>
concept Settings = requires(S s) { S::kSection; };

// A settings struct may also say which of its fields its current values make derived from
// elsewhere (an area light's position, placed from its emitter every frame): readOnly(key)
// returns why, or nullptr for a field one can edit. The editor's panels draw such a field
// disabled, with the reason in its tooltip; JSON and --set are not affected.
template <class S>
concept HasReadOnlyFields = requires(const S& s, std::string_view key) {
    { s.readOnly(key) } -> std::convertible_to<const char*>;
};

// A settings section that drives a pass declares, besides kSection:
//   static constexpr PassRole kRole;                     technique (chosen by the preset's
//                                                        `technique` key) or effect (always present)
//   static std::unique_ptr<Pass> createPass();           defined beside the pass
//   static size_t estimateBytes(const FrameSettings&);   GPU bytes, known before allocation
// and optionally
//   static void checkTime(const FrameSettings&);         throws past render.timeBudgetSeconds
//   static std::string notes(const FrameSettings&);      warnings for the user, "" when none
// The section list (gi/render/render_settings.h) registers it (gi/render/pass.h).
class Pass;
struct FrameSettings;
enum class PassRole { Technique, Effect };

template <class S>
concept PassSettings = Settings<S> && requires(const FrameSettings& fs) {
    S::kRole;
    S::createPass();
    { S::estimateBytes(fs) } -> std::convertible_to<size_t>;
};

}  // namespace gi
