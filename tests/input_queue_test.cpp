// The editor's key queue (ui/input_queue.h): no tap is lost however long a frame takes.
#include "ui/input_queue.h"

#include <gtest/gtest.h>

#include <vector>

namespace gi::ui {
namespace {

constexpr int kBackspace = 259, kCtrl = 341, kA = 65, kRelease = 0, kPress = 1, kRepeat = 2;

// One "frame": the events ImGui is given, in order.
std::vector<KeyEvent> frame(KeyEventQueue& q) {
    std::vector<KeyEvent> seen;
    q.drain([&](const KeyEvent& e) { seen.push_back(e); });
    return seen;
}

TEST(KeyEventQueue, ATapWithinOneFrameIsDownForOneFrameThenUp) {
    KeyEventQueue q;
    q.push({kBackspace, 0, kPress, 0});
    q.push({kBackspace, 0, kRelease, 0});
    std::vector<KeyEvent> first = frame(q);
    ASSERT_EQ(first.size(), 1u);
    EXPECT_EQ(first[0].action, kPress) << "the key is seen down for a whole frame";
    std::vector<KeyEvent> second = frame(q);
    ASSERT_EQ(second.size(), 1u);
    EXPECT_EQ(second[0].action, kRelease);
    EXPECT_TRUE(frame(q).empty());
}

TEST(KeyEventQueue, KeepsOrderAcrossKeysAndPassesRepeats) {
    KeyEventQueue q;
    // Ctrl+A typed quickly, then Backspace tapped twice, all within one slow frame.
    for (KeyEvent e : {KeyEvent{kCtrl, 0, kPress, 0}, KeyEvent{kA, 0, kPress, 2}, KeyEvent{kA, 0, kRepeat, 2},
                       KeyEvent{kA, 0, kRelease, 2}, KeyEvent{kCtrl, 0, kRelease, 0}, KeyEvent{kBackspace, 0, kPress, 0},
                       KeyEvent{kBackspace, 0, kRelease, 0}, KeyEvent{kBackspace, 0, kPress, 0},
                       KeyEvent{kBackspace, 0, kRelease, 0}})
        q.push(e);
    std::vector<KeyEvent> f1 = frame(q);
    ASSERT_EQ(f1.size(), 3u) << "Ctrl down, A down, A's repeat; A's release waits";
    EXPECT_EQ(f1[1].key, kA);
    EXPECT_EQ(f1[2].action, kRepeat);
    std::vector<KeyEvent> f2 = frame(q);
    ASSERT_EQ(f2.size(), 3u) << "A up, Ctrl up, Backspace down; its release waits";
    EXPECT_EQ(f2[0].key, kA);
    EXPECT_EQ(f2[2].key, kBackspace);
    EXPECT_EQ(frame(q).size(), 1u);  // Backspace up; the second press must wait for it
    std::vector<KeyEvent> f4 = frame(q);
    ASSERT_EQ(f4.size(), 1u);
    EXPECT_EQ(f4[0].action, kPress) << "the second tap is a second press";
    EXPECT_EQ(frame(q).size(), 1u);
    EXPECT_EQ(q.pending(), 0u);
}

TEST(KeyEventQueue, ACharacterAfterAKeyChangeWaitsForTheNextFrame) {
    // End, then Q typed, then Backspace, within one frame: a text field applies characters before
    // keys, so Q must come a frame after End (appended, not inserted at the cursor).
    KeyEventQueue q;
    constexpr int kEnd = 269;
    q.push({kEnd, 0, kPress, 0});
    q.push({kEnd, 0, kRelease, 0});
    q.push({0, 0, 0, 0, 'Q'});
    q.push({kBackspace, 0, kPress, 0});
    q.push({kBackspace, 0, kRelease, 0});
    std::vector<KeyEvent> f1 = frame(q);
    ASSERT_EQ(f1.size(), 1u);
    EXPECT_EQ(f1[0].key, kEnd);
    std::vector<KeyEvent> f2 = frame(q);
    ASSERT_EQ(f2.size(), 1u) << "End's release is a change, so Q waits again";
    std::vector<KeyEvent> f3 = frame(q);
    ASSERT_EQ(f3.size(), 2u) << "Q, then Backspace down in the same frame (characters go in before keys)";
    EXPECT_EQ(f3[0].codepoint, unsigned('Q'));
    EXPECT_EQ(f3[1].key, kBackspace);
    EXPECT_EQ(frame(q).size(), 1u);
    EXPECT_EQ(q.pending(), 0u);
}

}  // namespace
}  // namespace gi::ui
