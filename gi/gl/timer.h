// Per-pass GPU times from GL_TIMESTAMP query pairs (GL_TIME_ELAPSED reads 0 around compute work
// on llvmpipe; timestamps match the wall clock). Two frames of queries are kept so the editor
// reads last frame's results without stalling; the runner waits for the current frame.
#pragma once

#include "gi/gl/handle.h"

#include <string>
#include <vector>

namespace gi::gl {

struct PassTime {
    std::string name;
    double gpuMs = 0.0;
};

class GpuTimer {
public:
    void beginFrame();
    void begin(const char* name);  // also pushes a debug group with the same name
    void end();
    void endFrame();
    // Reads the newest finished frame. With wait, blocks until the frame just ended is done.
    void resolve(bool wait);
    const std::vector<PassTime>& results() const { return mResults; }
    // Serialised timing: finish all GL work at every pass boundary and read the CPU clock there
    // instead of GL timestamps. On llvmpipe timestamp pairs do not bracket the work reliably:
    // draws are rasterised when the scene is flushed, so a raster pass's end stamp can land after
    // the compute passes that follow it (a 8.4 s volumetric march was counted under "lighting"),
    // and after the first frame a 9 s march read 0.1 ms between its stamps even with glFinish
    // around them. All llvmpipe work runs on the CPU, so finish + wall clock is its true cost.
    // The Renderer turns this on for software renderers; on a GPU it would stall the pipeline.
    void setSerialize(bool on) { mSerialize = on; }
    double totalMs() const;

    class Scope {
    public:
        Scope(GpuTimer& t, const char* name) : mTimer(t) { mTimer.begin(name); }
        ~Scope() { mTimer.end(); }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        GpuTimer& mTimer;
    };
    Scope scope(const char* name) { return Scope(*this, name); }

private:
    struct Entry {
        std::string name;
        GLuint begin, end;
        double cpuBegin = 0.0, cpuEnd = 0.0;  // ms, serialised timing
    };
    struct Frame {
        std::vector<Entry> entries;
        std::vector<Query> pool;
        size_t used = 0;
        bool pending = false;
    };
    Frame mFrames[2];
    int mCurrent = 0;
    std::vector<size_t> mOpen;
    std::vector<PassTime> mResults;
    bool mSerialize = false;

    GLuint nextQuery(Frame& f);
    bool read(Frame& f, bool wait);
};

}  // namespace gi::gl
