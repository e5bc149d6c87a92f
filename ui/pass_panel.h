// A pass's own editor panel, for what the generic parts cannot show: the settings window draws
// every section's fields from the reflection table, the pass's notes (gi/render/pass.h PassInfo)
// and its previewers (overlays over the viewport, images in windows) with no code per pass.
// A pass that wants more (VCT's voxel view, the phase function plot, the roughness mips table)
// adds a PassPanel in ui/panels/ and one line to the table in ui/pass_panels.cpp.
#pragma once

#include "gi/preset/preset.h"
#include "gi/render/renderer.h"
#include "gi/scene/scene.h"
#include "ui/panel_util.h"

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace gi::ui {

struct EditorOptions;

// What a panel may read and edit.
struct PanelContext {
    Preset& preset;
    const Scene& scene;
    // Null while the GI thread renders: then no GL call either, and the panel shows what it last
    // made (ui/gi_thread.h).
    Renderer* renderer;
    const std::string& frameError;  // the last frame's error, "" when it rendered
    int width, height;              // the frame's size
};

class PassPanel {
public:
    virtual ~PassPanel() = default;
    // Whether the pass's section starts open (besides the active technique's, which always does).
    virtual bool openAtStart() const { return false; }
    // Below the section's fields; returns the OR of the Cost bits of what it changed.
    virtual uint8_t drawSection(PanelContext&) { return 0; }
    // Into the viewport (its rectangle of ViewportRect::framebuffer) after the frame is drawn there;
    // only while the GI context is held.
    virtual void drawViewport(PanelContext&, const FrameSettings&, const ViewportRect&) {}
    // Whether drawViewport draws anything with these settings (the viewport is then composed on
    // every frame, not only when the GI image changes).
    virtual bool drawsViewport(const FrameSettings&) const { return false; }
    // Its own windows.
    virtual void drawWindows(PanelContext&) {}
};

struct PassPanelEntry {
    std::string_view section;  // the pass's settings section
    std::unique_ptr<PassPanel> (*create)(const EditorOptions& options);
};
// Every pass panel; a pass without one is shown by the generic parts alone.
const std::vector<PassPanelEntry>& passPanels();

}  // namespace gi::ui
