#include "gi/gl/timer.h"

#include "gi/util/error.h"

#include <chrono>

namespace gi::gl {

namespace {
double nowMs() { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

GLuint GpuTimer::nextQuery(Frame& f) {
    if (f.used == f.pool.size()) {
        GLuint id = 0;
        glCreateQueries(GL_TIMESTAMP, 1, &id);
        f.pool.emplace_back(id);
    }
    return f.pool[f.used++].id();
}

void GpuTimer::beginFrame() {
    Frame& f = mFrames[mCurrent];
    if (f.pending) read(f, true);  // two frames behind: must be finished by now
    f.entries.clear();
    f.used = 0;
}

void GpuTimer::begin(const char* name) {
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
    if (mSerialize) glFinish();
    Frame& f = mFrames[mCurrent];
    GLuint q = nextQuery(f);
    glQueryCounter(q, GL_TIMESTAMP);
    f.entries.push_back({name, q, 0, mSerialize ? nowMs() : 0.0, 0.0});
    mOpen.push_back(f.entries.size() - 1);
}

void GpuTimer::end() {
    GI_ASSERT(!mOpen.empty(), "GpuTimer::end without begin");
    Frame& f = mFrames[mCurrent];
    if (mSerialize) {
        glFinish();
        f.entries[mOpen.back()].cpuEnd = nowMs();
    }
    GLuint q = nextQuery(f);
    glQueryCounter(q, GL_TIMESTAMP);
    f.entries[mOpen.back()].end = q;
    mOpen.pop_back();
    glPopDebugGroup();
}

void GpuTimer::endFrame() {
    GI_ASSERT(mOpen.empty(), "GpuTimer::endFrame with an open pass");
    mFrames[mCurrent].pending = true;
    mCurrent ^= 1;
}

bool GpuTimer::read(Frame& f, bool wait) {
    if (!f.pending) return false;
    if (!wait && !f.entries.empty()) {
        GLint available = 0;
        glGetQueryObjectiv(f.entries.back().end, GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) return false;
    }
    std::vector<PassTime> out;
    for (const Entry& e : f.entries) {
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(e.begin, GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(e.end, GL_QUERY_RESULT, &t1);
        double ms = t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0;
        if (mSerialize) ms = e.cpuEnd - e.cpuBegin;
        out.push_back({e.name, ms});
    }
    f.pending = false;
    mResults = std::move(out);
    return true;
}

void GpuTimer::resolve(bool wait) {
    Frame& last = mFrames[mCurrent ^ 1];  // the frame that just ended
    if (wait) {
        read(last, true);
        return;
    }
    if (!read(last, false)) read(mFrames[mCurrent], false);
}

double GpuTimer::totalMs() const {
    double t = 0;
    for (auto& r : mResults) t += r.gpuMs;
    return t;
}

}  // namespace gi::gl
