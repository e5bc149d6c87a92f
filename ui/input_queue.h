// Key and character events queued between GLFW and Dear ImGui, so that no tap is lost at a low
// frame rate. ImGui 1.86 (Debian's) reads which keys are down once per frame: a key pressed and
// released within one frame (a Backspace tap during a 1 s frame) was never seen down. The window
// queues GLFW's key and character events here and hands them to ImGui at most one state change per
// key per frame, in the order they came: a tap becomes "down" for one frame and "up" the next.
// A text field applies a frame's characters before its keys, so a character typed after a key
// change waits for the next frame (End then Q appends Q; in one frame Q would go in first). No
// GLFW or ImGui in this header, so tests check the rules without a window.
#pragma once

#include <cstddef>
#include <deque>

namespace gi::ui {

struct KeyEvent {
    int key = 0;
    int scancode = 0;
    int action = 0;  // GLFW_RELEASE 0, GLFW_PRESS 1, GLFW_REPEAT 2
    int mods = 0;
    unsigned codepoint = 0;  // a typed character (key, action and mods unused), else 0
};

class KeyEventQueue {
public:
    static constexpr int kRepeat = 2;

    void push(const KeyEvent& e) { mEvents.push_back(e); }
    size_t pending() const { return mEvents.size(); }

    // Hands the queued events to `apply` in order, stopping before the first event that would
    // change a key a second time this frame (press then release of one key), or a character that
    // follows a key change; that event and all after it wait for the next frame. Repeats change
    // nothing and pass. Returns how many went.
    template <class Apply>
    size_t drain(Apply&& apply) {
        size_t done = 0;
        int changed[kMaxChangesPerFrame];
        int count = 0;
        while (!mEvents.empty()) {
            const KeyEvent& e = mEvents.front();
            if (e.codepoint != 0) {
                if (count > 0) break;  // after a key change: next frame, so the text sees the key first
            } else if (e.action != kRepeat) {
                bool again = false;
                for (int i = 0; i < count; ++i) again |= changed[i] == e.key;
                if (again || count == kMaxChangesPerFrame) break;
                changed[count++] = e.key;
            }
            apply(e);
            mEvents.pop_front();
            ++done;
        }
        return done;
    }

private:
    static constexpr int kMaxChangesPerFrame = 64;
    std::deque<KeyEvent> mEvents;
};

}  // namespace gi::ui
