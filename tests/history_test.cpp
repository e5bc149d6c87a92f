// The editor's undo history and preset diff (gi/preset/history.h), without a window.
#include "gi/preset/history.h"

#include <gtest/gtest.h>

namespace gi {
namespace {

TEST(PresetDiff, NamesEveryChangedKeyWithItsValues) {
    Preset a, b;
    EXPECT_TRUE(presetDiff(a, b).empty());
    b.vct.nudge = 2.5f;
    b.header.scene = "basic";
    b.camera.eye.y = 1.5f;
    std::vector<PresetChange> d = presetDiff(a, b);
    ASSERT_EQ(d.size(), 3u);
    std::map<std::string, PresetChange> byKey;
    for (const auto& c : d) byKey[c.key] = c;
    EXPECT_EQ(byKey["vct.nudge"].before, "3.0");
    EXPECT_EQ(byKey["vct.nudge"].after, "2.5");
    EXPECT_EQ(byKey["scene"].after, "\"basic\"");
    EXPECT_EQ(byKey["camera.eye"].after, "[0.0,1.5,3.4]");

    Preset c = a;
    c.lightsFromScene = false;
    c.lights.push_back(LightSettings{});
    ASSERT_EQ(presetDiff(a, c).size(), 1u);
    EXPECT_EQ(presetDiff(a, c)[0].key, "lights");
    Preset e = c;
    e.lights[0].intensity = 7.0f;
    e.lights.push_back(LightSettings{});
    std::vector<PresetChange> le = presetDiff(c, e);
    EXPECT_EQ(le.front().key, "lights.0.intensity");
    EXPECT_GT(le.size(), 2u) << "the added light's keys";
    EXPECT_EQ(le.back().before, "") << "a light only one side has";
}

TEST(PresetHistory, UndoRedoAndANewEditDropsTheRedoTail) {
    PresetHistory h;
    Preset p;
    h.reset(p, "opened");
    EXPECT_FALSE(h.canUndo());
    EXPECT_FALSE(h.record(p)) << "no change, no step";
    p.vct.nudge = 2.0f;
    EXPECT_TRUE(h.record(p));
    EXPECT_EQ(h.label(1), "vct.nudge 3.0 -> 2.0");
    p.lpv.gridResolution = 16;
    p.lpv.propagationSteps = 16;
    EXPECT_TRUE(h.record(p));
    EXPECT_EQ(h.label(2), "2 settings: lpv.gridResolution, lpv.propagationSteps");
    EXPECT_EQ(h.undo().lpv.gridResolution, 32);
    EXPECT_EQ(h.undo().vct.nudge, 3.0f);
    EXPECT_FALSE(h.canUndo());
    EXPECT_EQ(h.undo().vct.nudge, 3.0f) << "undo past the first state stays there";
    EXPECT_EQ(h.redo().vct.nudge, 2.0f);
    EXPECT_TRUE(h.canRedo());
    Preset q = h.current();
    q.vct.coneAperture = 45.0f;
    EXPECT_TRUE(h.record(q));
    EXPECT_FALSE(h.canRedo()) << "an edit after an undo ends the redo branch";
    EXPECT_EQ(h.size(), 3u);
    EXPECT_EQ(h.jump(0).vct.nudge, 3.0f);
    EXPECT_EQ(h.jump(99).vct.coneAperture, 45.0f) << "jump clamps to the last state";
}

TEST(PresetHistory, KeepsAtMostItsLimit) {
    PresetHistory h(4);
    Preset p;
    h.reset(p, "opened");
    for (int i = 1; i <= 10; ++i) {
        p.vct.gridResolution = 32 + i;
        h.record(p);
    }
    EXPECT_EQ(h.size(), 4u);
    EXPECT_EQ(h.current().vct.gridResolution, 42);
    EXPECT_EQ(h.jump(0).vct.gridResolution, 39) << "the oldest states go first";
}

}  // namespace
}  // namespace gi
