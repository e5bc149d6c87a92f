#include "gi/envmap/environment.h"

#include "gi/render/strokes.h"

#include "common/shared.h"
#include "gi/preset/reflect.h"
#include "gi/util/error.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace gi {

using namespace shared;

namespace {

constexpr int kLUTSize = 128;
constexpr int kLUTSamples = 512;
constexpr int kIrradianceSize = 32;

// Wrap S (the latlong's u) as given, T and R clamped.
gl::Sampler makeSampler(GLenum minFilter, GLenum wrapS) {
    return gl::createSampler({minFilter, minFilter == GL_NEAREST ? GLenum(GL_NEAREST) : GLenum(GL_LINEAR), wrapS, GL_CLAMP_TO_EDGE,
                              GL_CLAMP_TO_EDGE});
}


// The fields shade and sky share.
EnvParams lookupParams(const EnvironmentSettings& s, int width, int height, const glm::mat4& invViewProj, const glm::vec3& eye) {
    EnvParams p{};
    p.invViewProj = invViewProj;
    p.eye = glm::vec4(eye, 1.0f);
    p.width = width;
    p.height = height;
    p.intensity = s.intensity;
    p.rotation = s.rotation;
    return p;
}

double nowMs() { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

int fullMipCount(int size) { return 1 + int(std::floor(std::log2(double(std::max(size, 1))))); }

// Prefilter throughput on Mesa 22.3 llvmpipe, 2 cores (the machines the suite runs on): GGX
// samples (one textureLod each) per second over the sampled mips, from gi-render's stats.json
// (environment.mips[].ms): 32 to 41 M/s on an idle machine (tests/bench/envmap_bench.sh: 256^2
// at 64 and 200 samples, 1024^2 at 64), 15 to 29 M/s with a compile running beside (256^2 to
// 1024^2, 64 to 2048 samples). The Beckmann cone costs about the same per sample. So cubeSize
// 2048 at 4096 samples is some 16 minutes. A real GPU is far faster: there the estimate is
// pessimistic, and render.timeBudgetSeconds is the setting to raise.
constexpr double kPrefilterSamplesPerSecond = 35e6;
// A dispatch is cut into bands of rows of about this much work, so progress comes while a large
// mip runs (and a GPU driver's watchdog never sees one long dispatch).
constexpr double kPrefilterSecondsPerDispatch = 0.5;

}  // namespace

int Environment::chainMipCount(const EnvironmentSettings& s) {
    return std::min({int(s.mipRoughness.size()), fullMipCount(s.cubeSize), kEnvMaxMips});
}

int Environment::chainMipOfEntry(const EnvironmentSettings& s, int entry) {
    int n = int(s.mipRoughness.size()), mips = chainMipCount(s);
    if (n <= mips || entry < mips - 1) return entry;
    return entry == n - 1 ? mips - 1 : -1;
}

float Environment::beckmannDiskRadius(float roughness) {
    // Seed 004 Fig. 3.24: roughness -> sampling disk radius tan(theta).
    static const float r[] = {0.0f, 0.01f, 0.05f, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 1.0f};
    static const float d[] = {0.0f, 0.01f, 0.1f, 0.21f, 0.42f, 0.62f, 0.83f, 1.07f, 1.27f, 1.48f, 2.14f};
    if (roughness <= 0.0f) return 0.0f;
    for (int i = 0; i + 1 < 11; ++i)
        if (roughness <= r[i + 1]) return d[i] + (d[i + 1] - d[i]) * (roughness - r[i]) / (r[i + 1] - r[i]);
    return d[10];
}

Environment::Environment()
    : mToCubeProg("environment.toCube", {{GL_COMPUTE_SHADER, "envmap/to_cube.comp"}}),
      mPrefilterProg("environment.prefilter", {{GL_COMPUTE_SHADER, "envmap/prefilter.comp"}}),
      mLUTProg("environment.brdfLUT", {{GL_COMPUTE_SHADER, "envmap/brdf_lut.comp"}}),
      mShadeProg("environment.shade", {{GL_COMPUTE_SHADER, "envmap/shade.comp"}}),
      mSkyProg("environment.sky", {{GL_COMPUTE_SHADER, "envmap/sky.comp"}}),
      mBlock(kEnvBlockName, kEnvBlockBinding) {
    for (gl::Program* p : {&mToCubeProg, &mPrefilterProg, &mLUTProg, &mShadeProg, &mSkyProg}) mBlock.requireIn(*p);
    mLinear = makeSampler(GL_LINEAR, GL_REPEAT);
    mCubeLinear = makeSampler(GL_LINEAR_MIPMAP_LINEAR, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(mCubeLinear.id(), GL_TEXTURE_CUBE_MAP_SEAMLESS, GL_TRUE);
    mPoint = makeSampler(GL_NEAREST, GL_CLAMP_TO_EDGE);
    computeLUT();
}

void Environment::computeLUT() {
    mLUT = gl::Texture::create2D(GL_RG16F, kLUTSize, kLUTSize);
    mLUTProg.use();
    EnvParams p{};
    p.size = kLUTSize;
    p.samples = kLUTSamples;
    mBlock.set(p);
    glBindImageTexture(kEnvImageTarget, mLUT.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG16F);
    glDispatchCompute(gl::groupCount(kLUTSize, shared::kGroup2D), gl::groupCount(kLUTSize, shared::kGroup2D), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

std::vector<float> Environment::chainRoughness(const EnvironmentSettings& s) {
    std::vector<float> table(size_t(chainMipCount(s)), 0.0f);
    for (int e = 0; e < int(s.mipRoughness.size()); ++e)
        if (int m = chainMipOfEntry(s, e); m >= 0) table[size_t(m)] = s.mipRoughness[size_t(e)];
    return table;
}

double Environment::estimateSamples(const EnvironmentSettings& s) {
    if (!s.enabled) return 0.0;
    // Mips of roughness 0 are copies; every other texel of every face takes `samples` samples.
    std::vector<float> table = chainRoughness(s);
    double texels = 0.0;
    for (size_t m = 0; m < table.size(); ++m)
        if (table[m] > 0.0f) texels += 6.0 * std::pow(double(std::max(s.cubeSize >> m, 1)), 2.0);
    return texels * double(s.samples);
}

double Environment::estimateSeconds(const EnvironmentSettings& s) { return estimateSamples(s) / kPrefilterSamplesPerSecond; }

void Environment::checkTimeBudget(const EnvironmentSettings& s, double budgetSeconds) {
    gi::checkTimeBudget(estimateSeconds(s), budgetSeconds, "environment prefilter",
                        "cubeSize " + std::to_string(s.cubeSize) + ", samples " + std::to_string(s.samples),
                        "lower environment.samples or environment.cubeSize");
}

size_t Environment::estimateBytes(const EnvironmentSettings& s) {
    if (!s.enabled) return 0;
    size_t face = size_t(s.cubeSize) * size_t(s.cubeSize) * 8 * 6;
    return face * 4 / 3 * 2 + size_t(kIrradianceSize) * kIrradianceSize * 8 * 6 + size_t(kLUTSize) * kLUTSize * 4;
}

void Environment::prepare(const EnvironmentSettings& s, gl::GpuTimer& timer, const RenderSettings& render, const ProgressSink& progress,
                          uint8_t changes) {
    if (!s.enabled) {
        if (mBuilt || ready()) {
            for (gl::Texture* t : {&mLatLong, &mSource, &mPrefiltered, &mIrradiance}) *t = gl::Texture();
            mImage = EnvironmentImage();
            mMips.clear();
            mBuilt = false;
        }
        return;
    }
    // Rebuilt when a setting the maps are built from changed (the table's Reallocate fields);
    // intensity, rotation and skybox apply at lookup.
    if (mBuilt && !any(Cost(changes), Cost::Reallocate)) return;
    checkTimeBudget(s, render.timeBudgetSeconds);  // before anything is loaded or allocated
    mBuilt = false;
    auto pass = timer.scope("environment.prefilter");
    double t0 = nowMs();
    if (mImage.source != s.file) mImage = loadEnvironment(s.file, {}, render.memoryBudgetBytes());
    // Uploaded bottom row first, as every GL image here is (so the debug view shows the zenith at
    // the top); to_cube.comp reads v = 1 - latLongUV's v.
    mLatLong = gl::Texture::create2D(GL_RGB32F, mImage.width, mImage.height);
    size_t row = size_t(mImage.width) * 3;
    std::vector<float> flipped(mImage.rgb.size());
    for (int y = 0; y < mImage.height; ++y)
        std::copy_n(&mImage.rgb[size_t(mImage.height - 1 - y) * row], row, &flipped[size_t(y) * row]);
    glTextureSubImage2D(mLatLong.id(), 0, 0, 0, mImage.width, mImage.height, GL_RGB, GL_FLOAT, flipped.data());

    int size = s.cubeSize, levels = fullMipCount(size), mips = chainMipCount(s);
    mSource = gl::Texture::createCube(GL_RGBA16F, size, levels);
    mToCubeProg.use();
    EnvParams cube{};
    cube.size = size;
    mBlock.set(cube);
    glBindTextureUnit(kEnvUnitSource, mLatLong.id());
    glBindSampler(kEnvUnitSource, mLinear.id());
    glBindImageTexture(kEnvImageTarget, mSource.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(gl::groupCount(size, shared::kGroup2D), gl::groupCount(size, shared::kGroup2D), 6);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glGenerateTextureMipmap(mSource.id());
    glFinish();
    mLoadMs = nowMs() - t0;

    mPrefiltered = gl::Texture::createCube(GL_RGBA16F, size, mips);
    mIrradiance = gl::Texture::createCube(GL_RGBA16F, kIrradianceSize);
    mPrefilterProg.use();
    EnvParams params{};
    params.sourceSize = size;
    glBindTextureUnit(kEnvUnitSource, mSource.id());
    glBindSampler(kEnvUnitSource, mCubeLinear.id());
    mMips.clear();
    // Progress after each band of rows: the fraction is of the estimated samples.
    const double totalSamples = std::max(estimateSamples(s), 1.0);
    double samplesDone = 0.0;
    const int mipsToReport = mips;
    const double tPrefilter = nowMs();  // the time left is reckoned from the dispatches alone
    // After each band of mip `mipsDone` and after each mip; the detail names the mip under way.
    auto report = [&](int mipsDone) {
        if (!progress) return;
        ProgressUpdate u;
        u.task = "environment prefilter";
        u.done = mipsDone;
        u.total = mipsToReport;
        u.unit = "mips";
        u.fraction = std::min(samplesDone / totalSamples, 1.0);
        u.seconds = (nowMs() - tPrefilter) / 1000.0;
        if (mipsDone < mipsToReport)
            u.detail = "mip " + std::to_string(mipsDone) + ", " + std::to_string(std::max(size >> mipsDone, 1)) + "^2, " +
                       std::to_string(s.samples) + " samples";
        progress(u);
    };
    auto dispatch = [&](const gl::Texture& dst, int level, int faceSize, int mode, float roughness, float disk, int samples,
                        int mip) {
        params.size = faceSize;
        params.mode = mode;
        params.roughness = roughness;
        params.diskRadius = disk;
        params.samples = samples;
        glBindImageTexture(kEnvImageTarget, dst.id(), level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        // Bands of rows (multiples of the 8-row work group) of about kPrefilterSecondsPerDispatch each.
        bool sampled = mode != kEnvPrefilterIrradiance && roughness > 0.0f;
        double rowSamples = sampled ? 6.0 * double(faceSize) * double(samples) : 0.0;
        int rows = faceSize;
        if (rowSamples > 0.0)
            rows = std::clamp(int(kPrefilterSamplesPerSecond * kPrefilterSecondsPerDispatch / rowSamples) / shared::kGroup2D * shared::kGroup2D,
                              shared::kGroup2D, faceSize);
        double start = nowMs();
        for (int row = 0; row < faceSize; row += rows) {
            int band = std::min(rows, faceSize - row);
            params.rowOffset = row;
            mBlock.set(params);
            glDispatchCompute(gl::groupCount(faceSize, shared::kGroup2D), gl::groupCount(band, shared::kGroup2D), 6);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            glFinish();
            samplesDone += rowSamples * double(band);
            if (mip >= 0 && row + band < faceSize) report(mip);
        }
        return nowMs() - start;
    };
    // A table longer than the cube's halvings keeps its first entries and its last (so the
    // roughest lobe stays reachable): 9 mips of a 256^2 cube take 0 ... 0.5 and 1 of the seed's 11.
    std::vector<float> table = chainRoughness(s);
    for (int m = 0; m < mips; ++m) {
        MipInfo info;
        info.roughness = table[size_t(m)];
        info.size = std::max(size >> m, 1);
        bool cone = s.distribution == PrefilterDistribution::BeckmannCone;
        info.diskRadius = cone ? beckmannDiskRadius(info.roughness) : 0.0f;
        info.samples = info.roughness > 0.0f ? s.samples : 0;
        info.ms = dispatch(mPrefiltered, m, info.size, cone ? kEnvPrefilterBeckmannCone : kEnvPrefilterGGX, info.roughness,
                           info.diskRadius, s.samples, m);
        mMips.push_back(info);
        report(m + 1);
    }
    mIrradianceSH = irradianceSH(mImage);
    for (int i = 0; i < 9; ++i) params.sh[i] = glm::vec4(mIrradianceSH[size_t(i)], 0.0f);
    dispatch(mIrradiance, 0, kIrradianceSize, kEnvPrefilterIrradiance, 1.0f, 0.0f, 1, -1);
    glBindSampler(kEnvUnitSource, 0);
    mBuilt = true;
}

void Environment::prepare(FrameContext& ctx) {
    const FrameSettings& fs = ctx.settings;
    prepare(fs.environment, ctx.timer, fs.render, ctx.progress, ctx.changes);
    ctx.brdfLUT = brdfLUT();
    if (fs.environment.enabled && fs.environment.intensity > 0.0f && ready()) {
        ctx.sky.prefiltered = mPrefiltered.id();
        ctx.sky.sampler = mCubeLinear.id();
        ctx.sky.irradianceSH = mIrradianceSH;
        ctx.sky.intensity = fs.environment.intensity;
        ctx.sky.rotation = fs.environment.rotation;
        ctx.sky.mipRoughness.clear();
        for (const MipInfo& m : mMips) ctx.sky.mipRoughness.push_back(m.roughness);
    }
}

void Environment::indirect(FrameContext& ctx) {
    // With technique none the environment is the indirect light; a technique's own wins.
    const FrameSettings& fs = ctx.settings;
    if (ctx.indirectWritten || fs.technique != TechniqueChoice::kNone || !fs.environment.enabled || !ready()) return;
    shade(fs.environment, ctx.normal, ctx.material, ctx.depth, ctx.indirect, ctx.indirectSpecular, ctx.width, ctx.height,
          ctx.invViewProj, fs.camera.eye, ctx.timer);
    ctx.indirectWritten = true;
}

void Environment::afterLighting(FrameContext& ctx) {
    const FrameSettings& fs = ctx.settings;
    if (fs.environment.enabled && fs.environment.skybox && ready())
        sky(fs.environment, ctx.depth, ctx.hdr, ctx.width, ctx.height, ctx.invViewProj, fs.camera.eye, ctx.timer);
}

std::vector<std::string> Environment::passNames(const FrameSettings& fs) const {
    const EnvironmentSettings& s = fs.environment;
    if (!s.enabled) return {};
    std::vector<std::string> names{"environment.prefilter"};  // on the frame that builds the maps
    if (fs.technique == TechniqueChoice::kNone) names.push_back("environment.shade");
    if (s.skybox) names.push_back("environment.sky");
    return names;
}

namespace {

constexpr int kMipTileWidth = 256, kMipTileHeight = 128;

}  // namespace

std::vector<Previewer> Environment::previewers(const FrameSettings& fs) const {
    std::vector<Previewer> out;
    if (!fs.environment.enabled || !ready() || mMips.empty()) return out;
    auto tile = [this](const PreviewContext& ctx, int m) {
        DebugView view;
        view.name = "environment.mip" + std::to_string(m);
        view.texture = prefiltered();
        view.target = GL_TEXTURE_CUBE_MAP;
        view.mode = shared::kViewCubeLatLong;
        view.width = kMipTileWidth;
        view.height = kMipTileHeight;
        view.level = m;
        return ctx.renderView(view, kMipTileWidth, kMipTileHeight);
    };
    for (int m = 0; m < int(mMips.size()); ++m) {
        char what[96];
        std::snprintf(what, sizeof what, "Mip %d of the prefiltered chain (roughness %.2f) as a latlong image", m,
                      double(mMips[size_t(m)].roughness));
        out.push_back({"environment.mip" + std::to_string(m), what,
                       [tile, m](const PreviewContext& ctx) { return PreviewImage{kMipTileWidth, kMipTileHeight, tile(ctx, m)}; },
                       {}});
    }
    auto sheet = [this, tile](const PreviewContext& ctx) {
        const int count = int(mMips.size()), tileW = kMipTileWidth, tileH = kMipTileHeight, gap = 4;
        const int columns = std::min(count, 4), rows = (count + columns - 1) / columns;
        PreviewImage img{columns * tileW + (columns - 1) * gap, rows * tileH + (rows - 1) * gap, {}};
        img.rgba.assign(size_t(img.width) * size_t(img.height) * 4, 24);
        for (size_t i = 3; i < img.rgba.size(); i += 4) img.rgba[i] = 255;
        for (int m = 0; m < count; ++m) {
            std::vector<uint8_t> t = tile(ctx, m);
            // Rows of the sheet count from the top; the images from the bottom.
            int x0 = m % columns * (tileW + gap), y0 = img.height - (m / columns + 1) * tileH - m / columns * gap;
            for (int y = 0; y < tileH; ++y)
                std::copy_n(&t[size_t(y) * tileW * 4], size_t(tileW) * 4, &img.rgba[(size_t(y0 + y) * img.width + size_t(x0)) * 4]);
            char roughness[16];
            std::snprintf(roughness, sizeof roughness, "%.2f", double(mMips[size_t(m)].roughness));
            const float h = 12.0f, top = float(y0 + tileH) - 6.0f - h, left = float(x0) + 6.0f;
            fillPolygon(img.rgba, img.width, img.height,
                        {{left - 3, top - 4}, {left + 66, top - 4}, {left + 66, top + h + 4}, {left - 3, top + h + 4}}, {0, 0, 0, 0.55f});
            std::vector<Stroke> label = segmentText(std::to_string(m), left, top, h, {1.0f, 0.85f, 0.2f, 1.0f});
            std::vector<Stroke> value = segmentText(roughness, left + 28.0f, top, h, {1, 1, 1, 1});
            label.insert(label.end(), value.begin(), value.end());
            drawStrokes(img.rgba, img.width, img.height, label);
        }
        return img;
    };
    out.push_back({"environment.mips", "Every mip of the prefiltered chain on one sheet, labelled with its index and roughness", sheet, {}});
    return out;
}

PassReport Environment::report(const FrameSettings& fs) const {
    PassReport r;
    if (!fs.environment.enabled || !ready()) return r;
    r.texts = {{"source", mImage.source}};
    r.numbers = {{"loadMs", mLoadMs}};
    r.tableName = "mips";
    r.columns = {"roughness", "size", "samples", "diskRadius", "ms"};
    for (const MipInfo& m : mMips) r.rows.push_back({m.roughness, double(m.size), double(m.samples), m.diskRadius, m.ms});
    return r;
}

std::unique_ptr<Pass> EnvironmentSettings::createPass() { return std::make_unique<Environment>(); }
size_t EnvironmentSettings::estimateBytes(const FrameSettings& fs) { return Environment::estimateBytes(fs.environment); }
void EnvironmentSettings::checkTime(const FrameSettings& fs) {
    if (fs.environment.enabled) Environment::checkTimeBudget(fs.environment, fs.render.timeBudgetSeconds);
}

void Environment::shade(const EnvironmentSettings& s, GLuint normal, GLuint material, GLuint depth, GLuint indirect, GLuint specular,
                        int width, int height, const glm::mat4& invViewProj, const glm::vec3& eye, gl::GpuTimer& timer) const {
    auto pass = timer.scope("environment.shade");
    mShadeProg.use();
    EnvParams p = lookupParams(s, width, height, invViewProj, eye);
    p.mipCount = int(mMips.size());
    // Past the chain the table reads 1, the roughest lobe.
    for (int m = 0; m < kEnvMaxMips; ++m) p.mipRoughness[m / 4][m % 4] = m < p.mipCount ? mMips[size_t(m)].roughness : 1.0f;
    mBlock.set(p);
    const GLuint units[3] = {GLuint(kUnitNormal), GLuint(kUnitMaterial), GLuint(kUnitDepth)};
    const GLuint textures[3] = {normal, material, depth};
    for (int i = 0; i < 3; ++i) {
        glBindTextureUnit(units[i], textures[i]);
        glBindSampler(units[i], mPoint.id());
    }
    glBindTextureUnit(kEnvUnitPrefiltered, mPrefiltered.id());
    glBindSampler(kEnvUnitPrefiltered, mCubeLinear.id());
    glBindTextureUnit(kEnvUnitIrradiance, mIrradiance.id());
    glBindSampler(kEnvUnitIrradiance, mCubeLinear.id());
    glBindImageTexture(kEnvImageIndirect, indirect, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glBindImageTexture(kEnvImageSpecular, specular, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    glDispatchCompute(gl::groupCount(width, shared::kGroup2D), gl::groupCount(height, shared::kGroup2D), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    for (GLuint u : {units[0], units[1], units[2], GLuint(kEnvUnitPrefiltered), GLuint(kEnvUnitIrradiance)}) glBindSampler(u, 0);
}

void Environment::sky(const EnvironmentSettings& s, GLuint depth, GLuint hdr, int width, int height, const glm::mat4& invViewProj,
                      const glm::vec3& eye, gl::GpuTimer& timer) const {
    auto pass = timer.scope("environment.sky");
    mSkyProg.use();
    mBlock.set(lookupParams(s, width, height, invViewProj, eye));
    glBindTextureUnit(kUnitDepth, depth);
    glBindSampler(kUnitDepth, mPoint.id());
    glBindTextureUnit(kEnvUnitPrefiltered, mPrefiltered.id());
    glBindSampler(kEnvUnitPrefiltered, mCubeLinear.id());
    glBindImageTexture(kEnvImageTarget, hdr, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glDispatchCompute(gl::groupCount(width, shared::kGroup2D), gl::groupCount(height, shared::kGroup2D), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    glBindSampler(kEnvUnitPrefiltered, 0);
    glBindSampler(kUnitDepth, 0);
}

std::vector<DebugView> Environment::debugViews() const {
    std::vector<DebugView> v;
    v.push_back({"brdfLUT", mLUT.id(), GL_TEXTURE_2D, kViewColor, kLUTSize, kLUTSize});
    if (!ready()) return v;
    v.push_back({"environment", mLatLong.id(), GL_TEXTURE_2D, kViewColor, mImage.width, mImage.height});
    v.push_back({"environment.prefiltered", mPrefiltered.id(), GL_TEXTURE_CUBE_MAP, kViewCubeCross, mPrefiltered.width() * 4 / 3,
                 mPrefiltered.width()});
    v.push_back({"environment.irradiance", mIrradiance.id(), GL_TEXTURE_CUBE_MAP, kViewCubeCross, kIrradianceSize * 4 / 3 * 4,
                 kIrradianceSize * 4});
    return v;
}

bool Environment::reloadShaders(std::string& log) {
    bool ok = true;
    for (gl::Program* p : {&mToCubeProg, &mPrefilterProg, &mLUTProg, &mShadeProg, &mSkyProg})
        if (!p->reload()) {
            ok = false;
            log += p->log() + "\n";
        }
    if (ok) {
        computeLUT();
        mBuilt = false;  // rebuild the maps with the new programs
    }
    return ok;
}

// The environment lights the scene through technique none's indirect term, and through the
// techniques that gather FrameContext::sky (their settings' kGathersSky); with any other it is
// the sky and nothing more (the reference still lights with it).
std::string EnvironmentSettings::notes(const FrameSettings& fs) {
    if (!fs.environment.enabled || fs.environment.intensity <= 0.0f || fs.technique == TechniqueChoice::kNone) return "";
    const PassInfo* technique = findPass(fs.technique);
    if (technique && technique->gathersSky) return "";
    return "the environment map does not light the scene with technique " + fs.technique +
           ", which gathers no sky light (it is drawn as the sky)";
}

}  // namespace gi
