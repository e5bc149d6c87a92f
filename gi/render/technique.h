// The interface every GI technique implements. A technique owns its GL objects, reads the
// G-buffer and the scene, and writes the indirect term (irradiance / pi, RGBA16F) that the
// lighting pass multiplies by the diffuse albedo. It holds no ImGui and no JSON.
#pragma once

#include "gi/gl/timer.h"
#include "gi/render/render_settings.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace gi {

class GPUScene;
struct DebugView;

// A shadow map the renderer drew this frame, for techniques that test light visibility (VCT
// injection). depth is 0 for lights that cast no shadows.
struct ShadowMapView {
    GLuint depth = 0;
    bool cube = false;          // point lights: a cube map of distance / far
    glm::mat4 viewProj{1.0f};   // 2D maps
    float far = 1.0f;           // cube maps
};

struct FrameContext {
    const FrameSettings& settings;
    const GPUScene& scene;
    glm::mat4 view, proj, viewProj, invViewProj;
    GLuint albedo, normal, material, depth;  // the G-buffer
    GLuint indirect;                         // output, RGBA16F image: every pixel is written
    GLuint indirectSpecular;                 // optional output, RGBA16F: specular radiance (cleared to 0)
    const std::vector<ShadowMapView>& shadows;  // one per light, as fs.lights
    int width, height;
    gl::GpuTimer& timer;                     // techniques time each pass under its own name
};

class Technique {
public:
    virtual ~Technique() = default;
    virtual void execute(const FrameContext& ctx) = 0;
    virtual std::vector<DebugView> debugViews() const = 0;
    // Memory held by the pass of that timer name (0 for passes it does not know).
    virtual size_t passMemory(const std::string& pass) const = 0;
    virtual size_t memoryBytes() const = 0;
    // Memory of each named volume or buffer it holds (stats.json "volumes"); may be empty.
    struct VolumeMemory {
        std::string name;
        std::string format;  // e.g. "64^3 RGBA16F, 7 mips"
        size_t bytes = 0;
    };
    virtual std::vector<VolumeMemory> volumeMemory() const { return {}; }
    virtual bool reloadShaders(std::string& log) = 0;
};

}  // namespace gi
