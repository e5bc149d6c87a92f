// The generic settings test: every settings struct goes through defaults -> JSON -> back, `{}`,
// wrong types, out-of-range and non-finite values, unknown keys and `--set` text, all driven by
// its visit() list so a new field is covered without touching this file.
#include "gi/preset/preset.h"

#include <gtest/gtest.h>

#include <map>

#include <algorithm>
#include <cmath>

namespace gi {
namespace {

template <class S>
class SettingsTest : public ::testing::Test {};

// The preset's own sections, then every frame section from the one section list, so a new
// technique's settings are covered with no edit here (SettingsList checks nothing is missed).
#define GI_SECTION_TYPE(Type, name) , Type
using AllSettings = ::testing::Types<PresetHeader, LightSettings, CameraSettings, ReferenceSettings,
                                     QualitySettings GI_FRAME_SECTIONS(GI_SECTION_TYPE)>;
#undef GI_SECTION_TYPE
TYPED_TEST_SUITE(SettingsTest, AllSettings);

TEST(SettingsList, TheTypedTestsCoverEverySectionOfAPreset) {
    std::vector<std::string> sections;
    Preset().forEachSection([&](const auto& s) { sections.emplace_back(std::decay_t<decltype(s)>::kSection); });
    std::vector<std::string> covered;
    [&]<class... S>(::testing::Types<S...>) { (covered.emplace_back(S::kSection), ...); }(AllSettings{});
    for (const std::string& s : sections)
        EXPECT_NE(std::find(covered.begin(), covered.end(), s), covered.end()) << "section " << s << " is not tested";
    EXPECT_EQ(covered.size(), sections.size() + 2) << "the header and a light besides the sections";
    for (const char* s : {"volumetric", "environment", "lpv", "vct", "ssao"})
        EXPECT_NE(std::find(covered.begin(), covered.end(), s), covered.end()) << s;
}

// A JSON value of the wrong type for a field of type T.
template <class T>
json wrongType() {
    if constexpr (std::is_same_v<T, std::string> || ReflectedEnum<T>) return 42;
    else if constexpr (std::is_same_v<T, bool>) return "yes";
    else return "not a number";
}

TYPED_TEST(SettingsTest, DefaultsRoundTripThroughJSON) {
    TypeParam defaults;
    json j = toJson(defaults);
    TypeParam back;
    // Start from values that differ, so a field the reader skips would show up.
    back.visit([](auto& f, const FieldMeta& m) {
        using T = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<T, bool>) f = !f;
        else if constexpr (std::is_same_v<T, std::string>) f = "other";
        else if constexpr (std::is_same_v<T, float> || std::is_same_v<T, int>) f = T(std::isfinite(m.max) ? m.max : 7);
    });
    fromJson(back, j, "test", "");
    EXPECT_EQ(toJson(back), j);
    EXPECT_EQ(diff(back, defaults), 0);
}

TYPED_TEST(SettingsTest, EmptyObjectKeepsDefaults) {
    TypeParam s;
    fromJson(s, json::object(), "test", "");
    EXPECT_EQ(toJson(s), toJson(TypeParam{}));
}

TYPED_TEST(SettingsTest, NonObjectIsRejected) {
    TypeParam s;
    EXPECT_THROW(fromJson(s, json::array(), "test", "x."), Error);
    EXPECT_THROW(fromJson(s, json(3), "test", "x."), Error);
}

TYPED_TEST(SettingsTest, EveryFieldRejectsWrongTypeNamingTheKey) {
    TypeParam s;
    s.visit([](auto& field, const FieldMeta& m) {
        using T = std::decay_t<decltype(field)>;
        json j = {{m.key, wrongType<T>()}};
        TypeParam target;
        json before = toJson(target);
        try {
            fromJson(target, j, "file.json", "sec.");
            ADD_FAILURE() << "no error for wrong type of " << m.key;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("sec.") + m.key), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("file.json"), std::string::npos) << e.what();
        }
        EXPECT_EQ(toJson(target), before) << "a failed read changed the settings";
    });
}

TYPED_TEST(SettingsTest, NumbersOutsideTheirRangeAreRejected) {
    TypeParam s;
    s.visit([](auto& field, const FieldMeta& m) {
        using T = std::decay_t<decltype(field)>;
        if constexpr (std::is_same_v<T, float> || std::is_same_v<T, int> || std::is_same_v<T, glm::vec3>) {
            for (double bad : {m.min - 1.0, m.max + 1.0}) {
                if (!std::isfinite(bad)) continue;
                json value = std::is_same_v<T, glm::vec3> ? json::array({0.0, bad, 0.0}) : json(bad);
                if constexpr (std::is_same_v<T, glm::vec3>) value = json::array({bad, bad, bad});
                TypeParam target;
                try {
                    fromJson(target, json{{m.key, value}}, "f", "");
                    ADD_FAILURE() << m.key << " accepted " << bad;
                } catch (const Error& e) {
                    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
                    EXPECT_NE(std::string(e.what()).find(m.key), std::string::npos) << e.what();
                }
            }
            // Non-finite numbers cannot be written in JSON text but can arrive from code.
            TypeParam target;
            json nan = std::is_same_v<T, glm::vec3> ? json::array({NAN, 0.0, 0.0}) : json(NAN);
            EXPECT_THROW(fromJson(target, json{{m.key, nan}}, "f", ""), Error) << m.key;
        }
    });
}

TYPED_TEST(SettingsTest, UnknownKeySuggestsTheNearest) {
    TypeParam s;
    std::string firstKey;
    s.visit([&](auto&, const FieldMeta& m) {
        if (firstKey.empty()) firstKey = m.key;
    });
    std::string typo = firstKey + "x";
    try {
        fromJson(s, json{{typo, 1}}, "f", "sec.");
        FAIL() << "unknown key accepted";
    } catch (const Error& e) {
        std::string msg = e.what();
        EXPECT_NE(msg.find("unknown key"), std::string::npos) << msg;
        EXPECT_NE(msg.find("did you mean 'sec." + firstKey + "'"), std::string::npos) << msg;
    }
}

TYPED_TEST(SettingsTest, SetFieldParsesTextAndValidates) {
    TypeParam s;
    s.visit([&](auto& field, const FieldMeta& m) {
        using T = std::decay_t<decltype(field)>;
        TypeParam target;
        json value = detail::write(field);
        std::string text = value.is_string() ? value.template get<std::string>() : value.dump();
        EXPECT_TRUE(setField(target, m.key, text, m.key)) << m.key << "=" << text;
        EXPECT_EQ(detail::write(field), [&] {
            json out;
            target.visit([&](auto& f2, const FieldMeta& m2) {
                if (std::string(m2.key) == m.key) out = detail::write(f2);
            });
            return out;
        }());
        if constexpr (std::is_same_v<T, float> || std::is_same_v<T, int>) {
            if (std::isfinite(m.max)) {
                EXPECT_THROW(setField(target, m.key, detail::formatNumber(m.max * 2 + 1), m.key), Error);
            }
        }
    });
    EXPECT_FALSE(setField(s, "noSuchKey", "1", "noSuchKey"));
}

TEST(Settings, EditDistanceAndNearest) {
    EXPECT_EQ(detail::editDistance("shadowMapSize", "shadowMapSize"), 0u);
    EXPECT_EQ(detail::editDistance("shadowMapSise", "shadowMapSize"), 1u);
    EXPECT_EQ(detail::nearest("exposre", {"op", "exposure"}), "exposure");
}

TEST(Settings, IntegerFieldsRejectFractions) {
    RenderSettings r;
    EXPECT_THROW(fromJson(r, json{{"shadowMapSize", 1024.5}}, "f", "render."), Error);
}

TEST(Settings, DiffReportsTheCostOfChangedFields) {
    RenderSettings a, b;
    b.shadowMapSize = 2048;
    EXPECT_TRUE(any(Cost(diff(a, b)), Cost::Reallocate));
    RenderSettings c;
    c.pcfRadius = 3.0f;
    EXPECT_EQ(diff(a, c), uint8_t(Cost::Uniform));
}

// Labels in words: camelCase splits and lowers, acronyms and a lone trailing capital stay; every
// key of every section gives a non-empty label with no double spaces.
TEST(Settings, ReadableKeys) {
    EXPECT_EQ(readableKey("shadowMapSize"), "shadow map size");
    EXPECT_EQ(readableKey("memoryBudgetMB"), "memory budget MB");
    EXPECT_EQ(readableKey("SHOrder"), "SH order");
    EXPECT_EQ(readableKey("fovY"), "fov Y");
    EXPECT_EQ(readableKey("pcfRadius"), "pcf radius");
    EXPECT_EQ(readableKey("gridResolution"), "grid resolution");
    EXPECT_EQ(readableKey("enabled"), "enabled");
    EXPECT_EQ(readableKey("level2Scale"), "level2 scale");
    Preset p;
    p.forEachSection([](auto& section) {
        section.visit([](auto&, const FieldMeta& m) {
            const std::string label = readableKey(m.key);
            EXPECT_FALSE(label.empty()) << m.key;
            EXPECT_EQ(label.find("  "), std::string::npos) << m.key;
            EXPECT_EQ(label.size(), std::string(m.key).size() + size_t(std::count(label.begin(), label.end(), ' '))) << m.key;
        });
    });
}

// forDevelopers marks the settings one debugs; --list-settings (and its JSON) says which. Every
// section an artist opens keeps something to tune; quality (test thresholds) is all developer.
TEST(Settings, DeveloperSettingsAreMarkedAndEverySectionKeepsSomethingToTune) {
    std::map<std::string, std::pair<int, int>> perSection;  // section -> (artist, developer)
    std::map<std::string, bool> developer;
    for (const SettingInfo& s : listSettings()) {
        developer[s.key] = s.developer;
        size_t dot = s.key.find('.');
        std::string section = dot == std::string::npos ? "" : s.key.substr(0, dot);
        (s.developer ? perSection[section].second : perSection[section].first)++;
        EXPECT_EQ(settingInfoToJson(s).contains("developer"), s.developer) << s.key;
    }
    for (const char* key : {"vct.nudge", "vct.stepMultiplier", "lpv.rsmResolution", "render.shadowBias", "ssao.sampleCount",
                            "volumetric.samples", "environment.cubeSize", "reference.seed", "quality.minSSIM", "camera.near"})
        EXPECT_TRUE(developer.at(key)) << key;
    for (const char* key : {"technique", "vct.intensity", "vct.gridResolution", "lpv.propagationSteps", "toneMap.exposure",
                            "volumetric.density", "volumetric.phase", "environment.intensity", "camera.fovY"})
        EXPECT_FALSE(developer.at(key)) << key;
    for (const auto& [section, counts] : perSection) {
        if (section == "quality") {
            EXPECT_EQ(counts.first, 0);
            continue;
        }
        EXPECT_GT(counts.first, 0) << "section '" << section << "' has nothing an artist tunes";
    }
}

}  // namespace
}  // namespace gi
