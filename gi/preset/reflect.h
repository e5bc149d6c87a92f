// Generic operations over any settings struct's visit() list: JSON in and out with validation,
// `key=value` assignment, listing, and diffing. Nothing here knows a particular struct.
#pragma once

#include "gi/preset/settings.h"
#include "gi/util/error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace gi {

using json = nlohmann::json;

// One row of --list-settings.
struct SettingInfo {
    std::string key;          // full dotted key, e.g. "render.shadowMapSize"
    std::string type;         // float, int, bool, vec3, string, enum
    std::string description;
    std::string unit;
    std::string cost;
    json defaultValue;
    double min = -kNoLimit;
    double max = kNoLimit;
    std::vector<std::string> choices;  // enum names
    bool developer = false;            // forDevelopers: debugged rather than tuned
};

namespace detail {

size_t editDistance(std::string_view a, std::string_view b);
std::string nearest(std::string_view key, const std::vector<std::string>& candidates);
std::string formatNumber(double v);
std::string rangeText(const FieldMeta& m);
std::string where(const std::string& context, const std::string& key);

inline void checkNumber(double v, const FieldMeta& m, const std::string& context,
                        const std::string& key) {
    if (!std::isfinite(v))
        throw Error(where(context, key) + ": value is not a finite number");
    if (v < m.min || v > m.max)
        throw Error(where(context, key) + ": " + formatNumber(v) + " is out of range " +
                    rangeText(m));
}

inline std::string typeName(const json& j) { return j.type_name(); }

// Per-type conversion. Each reads a JSON value into the field with validation, or writes it.
inline void read(float& f, const json& j, const FieldMeta& m, const std::string& c,
                 const std::string& k) {
    if (!j.is_number()) throw Error(where(c, k) + ": expected a number, got " + typeName(j));
    double v = j.get<double>();
    checkNumber(v, m, c, k);
    f = float(v);
}
inline void read(int& i, const json& j, const FieldMeta& m, const std::string& c,
                 const std::string& k) {
    if (!j.is_number()) throw Error(where(c, k) + ": expected an integer, got " + typeName(j));
    double v = j.get<double>();
    if (std::isfinite(v) && v != std::floor(v))
        throw Error(where(c, k) + ": expected an integer, got " + formatNumber(v));
    checkNumber(v, m, c, k);
    i = int(v);
}
inline void read(bool& b, const json& j, const FieldMeta&, const std::string& c,
                 const std::string& k) {
    if (!j.is_boolean()) throw Error(where(c, k) + ": expected true or false, got " + typeName(j));
    b = j.get<bool>();
}
inline void read(std::string& s, const json& j, const FieldMeta&, const std::string& c,
                 const std::string& k) {
    if (!j.is_string()) throw Error(where(c, k) + ": expected a string, got " + typeName(j));
    s = j.get<std::string>();
}
inline void read(glm::vec3& v, const json& j, const FieldMeta& m, const std::string& c,
                 const std::string& k) {
    if (!j.is_array() || j.size() != 3)
        throw Error(where(c, k) + ": expected an array of 3 numbers");
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        if (!j[i].is_number())
            throw Error(where(c, k) + "[" + std::to_string(i) + "]: expected a number, got " +
                        typeName(j[i]));
        double x = j[i].get<double>();
        checkNumber(x, m, c, k + "[" + std::to_string(i) + "]");
        out[i] = float(x);
    }
    v = out;
}
// A list of numbers (e.g. a roughness per mip): 1 to kMaxListLength entries, each in the range.
inline constexpr size_t kMaxListLength = 32;
inline void read(std::vector<float>& v, const json& j, const FieldMeta& m, const std::string& c,
                 const std::string& k) {
    if (!j.is_array() || j.empty() || j.size() > kMaxListLength)
        throw Error(where(c, k) + ": expected an array of 1 to " + std::to_string(kMaxListLength) + " numbers");
    std::vector<float> out;
    for (size_t i = 0; i < j.size(); ++i) {
        std::string ki = k + "[" + std::to_string(i) + "]";
        if (!j[i].is_number()) throw Error(where(c, ki) + ": expected a number, got " + typeName(j[i]));
        double x = j[i].get<double>();
        checkNumber(x, m, c, ki);
        out.push_back(float(x));
    }
    v = out;
}
template <ReflectedEnum E>
void read(E& e, const json& j, const FieldMeta&, const std::string& c, const std::string& k) {
    std::vector<std::string> names;
    for (const auto& [v, name] : EnumNames<E>::values) names.push_back(name);
    if (j.is_string()) {
        std::string s = j.get<std::string>();
        for (const auto& [v, name] : EnumNames<E>::values)
            if (s == name) {
                e = v;
                return;
            }
        std::string all;
        for (auto& n : names) all += (all.empty() ? "" : ", ") + n;
        throw Error(where(c, k) + ": unknown value '" + s + "' (valid: " + all + ")");
    }
    throw Error(where(c, k) + ": expected one of the names, got " + typeName(j));
}

template <ChoiceString T>
void read(T& t, const json& j, const FieldMeta&, const std::string& c, const std::string& k) {
    std::vector<std::string> names = T::choices();
    if (!j.is_string()) throw Error(where(c, k) + ": expected one of the names, got " + typeName(j));
    std::string s = j.get<std::string>();
    for (const auto& n : names)
        if (s == n) {
            t.name = s;
            return;
        }
    std::string all;
    for (auto& n : names) all += (all.empty() ? "" : ", ") + n;
    throw Error(where(c, k) + ": unknown value '" + s + "' (valid: " + all + ")");
}

// A float as the double its shortest decimal text reads back to (3.4f as 3.4, not
// 3.4000000953674316), so written JSON holds what was typed and still reads back bit-exact.
double shortestDouble(float f);
inline json write(float f) { return shortestDouble(f); }
inline json write(int i) { return i; }
inline json write(bool b) { return b; }
inline json write(const std::string& s) { return s; }
inline json write(const glm::vec3& v) { return json::array({shortestDouble(v.x), shortestDouble(v.y), shortestDouble(v.z)}); }
inline json write(const std::vector<float>& v) {
    json j = json::array();
    for (float f : v) j.push_back(shortestDouble(f));
    return j;
}
template <ReflectedEnum E>
json write(E e) {
    return enumName(e);
}
template <ChoiceString T>
json write(const T& t) {
    return t.name;
}

template <class T> const char* typeOf() {
    if constexpr (std::is_same_v<T, float>) return "float";
    else if constexpr (std::is_same_v<T, int>) return "int";
    else if constexpr (std::is_same_v<T, bool>) return "bool";
    else if constexpr (std::is_same_v<T, std::string>) return "string";
    else if constexpr (std::is_same_v<T, glm::vec3>) return "vec3";
    else if constexpr (std::is_same_v<T, std::vector<float>>) return "list";
    else return "enum";
}

}  // namespace detail

template <Settings S>
json toJson(const S& s) {
    json j = json::object();
    const_cast<S&>(s).visit([&](auto& field, const FieldMeta& m) { j[m.key] = detail::write(field); });
    return j;
}

// The fields whose change costs `cost` (e.g. Cost::Reallocate: what GPU resources are built
// from), as toJson writes them: a key for "rebuild when these changed".
template <Settings S>
json toJson(const S& s, Cost cost) {
    json j = json::object();
    const_cast<S&>(s).visit([&](auto& field, const FieldMeta& m) {
        if (any(m.cost, cost)) j[m.key] = detail::write(field);
    });
    return j;
}

// Reads `j` into `s`, field by field. Keys absent from `j` keep their current values. Unknown
// keys, wrong types, non-finite and out-of-range numbers throw gi::Error naming
// "<context>: key '<prefix><key>'". All fields are validated before any is assigned, so `s` is
// unchanged when this throws.
template <Settings S>
void fromJson(S& s, const json& j, const std::string& context, const std::string& prefix) {
    if (!j.is_object())
        throw Error(detail::where(context, prefix.empty() ? std::string(S::kSection) : prefix.substr(0, prefix.size() - 1)) +
                    ": expected an object, got " + j.type_name());
    std::vector<std::string> keys;
    s.visit([&](auto&, const FieldMeta& m) { keys.emplace_back(m.key); });
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool known = false;
        for (auto& k : keys) known |= (k == it.key());
        if (!known)
            throw Error(detail::where(context, prefix + it.key()) + ": unknown key (did you mean '" +
                        prefix + detail::nearest(it.key(), keys) + "'?)");
    }
    S copy = s;
    copy.visit([&](auto& field, const FieldMeta& m) {
        auto it = j.find(m.key);
        if (it != j.end()) detail::read(field, *it, m, context, prefix + m.key);
    });
    s = copy;
}

// Sets one field from text, as `--set key=value` and the editor's console give it. The text is
// parsed as JSON (numbers, true/false, [x,y,z]); anything else is taken as a string.
template <Settings S>
bool setField(S& s, const std::string& key, const std::string& valueText, const std::string& fullKey) {
    json value;
    try {
        value = json::parse(valueText, nullptr, false);
    } catch (const json::exception&) {
        value = json(json::value_t::discarded);  // a number past a double's range (1e999) throws even so
    }
    if (value.is_discarded()) value = valueText;
    bool found = false;
    S copy = s;
    copy.visit([&](auto& field, const FieldMeta& m) {
        if (key == m.key) {
            detail::read(field, value, m, "--set", fullKey);
            found = true;
        }
    });
    if (found) s = copy;
    return found;
}

template <Settings S>
std::vector<std::string> fieldKeys(const std::string& prefix) {
    std::vector<std::string> keys;
    S s;
    s.visit([&](auto&, const FieldMeta& m) { keys.push_back(prefix + m.key); });
    return keys;
}

template <Settings S>
void describe(std::vector<SettingInfo>& out, const std::string& prefix) {
    S s;
    s.visit([&](auto& field, const FieldMeta& m) {
        using T = std::decay_t<decltype(field)>;
        SettingInfo info;
        info.key = prefix + m.key;
        info.type = detail::typeOf<T>();
        info.description = m.description;
        info.unit = m.unit;
        info.cost = costName(m.cost);
        info.defaultValue = detail::write(field);
        info.developer = m.developer;
        if constexpr (std::is_same_v<T, float> || std::is_same_v<T, int> || std::is_same_v<T, glm::vec3>) {
            info.min = m.min;
            info.max = m.max;
        }
        if constexpr (ReflectedEnum<T>)
            for (const auto& [v, name] : EnumNames<T>::values) info.choices.emplace_back(name);
        if constexpr (ChoiceString<T>) info.choices = T::choices();
        out.push_back(std::move(info));
    });
}

// The OR of the costs of every field that differs between a and b; 0 when equal.
template <Settings S>
uint8_t diff(const S& a, const S& b) {
    uint8_t cost = 0;
    S copyA = a;
    std::vector<json> values;
    copyA.visit([&](auto& field, const FieldMeta&) { values.push_back(detail::write(field)); });
    size_t i = 0;
    const_cast<S&>(b).visit([&](auto& field, const FieldMeta& m) {
        if (detail::write(field) != values[i++]) cost |= uint8_t(m.cost);
    });
    return cost;
}

}  // namespace gi
