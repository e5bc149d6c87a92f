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

    GLuint nextQuery(Frame& f);
    bool read(Frame& f, bool wait);
};

}  // namespace gi::gl
