#include "gi/reference/path_tracer.h"

#include "common/ggx.h"
#include "common/light.h"

#include "gi/envmap/envmap_image.h"
#include "gi/render/lights.h"
#include "gi/scene/camera.h"
#include "gi/util/error.h"
#include "gi/util/sampling.h"
#include "gi/volumetric/medium.h"

#include <embree3/rtcore.h>
#include <glm/gtc/constants.hpp>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

namespace gi {

namespace {

using shared::kPi;

uint64_t mix64(uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdULL;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ULL;
    x ^= x >> 33;
    return x;
}

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
float maxComponent(const glm::vec3& c) { return std::max(c.r, std::max(c.g, c.b)); }


// The raster pipeline's GGX terms, from the header the shaders include too.
using ggx::D_GGX;
using ggx::F_Schlick;
using ggx::G1_GGX;
using ggx::V_SmithGGXCorrelated;

// Surface properties at a hit, everything in world space.
struct Surface {
    glm::vec3 baseColor{1.0f};
    float metallic = 0.0f;
    float alpha = 1.0f;  // GGX alpha
    bool specular = true;
};

struct BSDFSample {
    glm::vec3 L{0.0f};
    glm::vec3 f{0.0f};
    float pdf = 0.0f;
};

class BSDF {
public:
    BSDF(const Surface& s, const glm::vec3& N, const glm::vec3& V) : mS(s), mN(N), mV(V) {
        basis(N, mT, mB);
        mNoV = std::max(glm::dot(N, V), 1e-4f);
        mF0 = glm::mix(glm::vec3(0.04f), s.baseColor, s.metallic);
        mDiffuse = s.baseColor * (1.0f - s.metallic);
        if (!s.specular) {
            mPSpec = 0.0f;
        } else {
            float spec = luminance(F_Schlick(mNoV, mF0));
            float diff = luminance(mDiffuse);
            mPSpec = diff <= 0.0f ? 1.0f : std::clamp(spec / (spec + diff), 0.1f, 0.9f);
        }
    }

    glm::vec3 eval(const glm::vec3& L) const {
        float NoL = glm::dot(mN, L);
        if (NoL <= 0.0f) return glm::vec3(0.0f);
        glm::vec3 f = mDiffuse / kPi;
        if (mS.specular) {
            glm::vec3 H = glm::normalize(mV + L);
            float NoH = std::max(glm::dot(mN, H), 0.0f);
            float VoH = std::max(glm::dot(mV, H), 0.0f);
            f += D_GGX(NoH, mS.alpha) * V_SmithGGXCorrelated(mNoV, NoL, mS.alpha) * F_Schlick(VoH, mF0);
        }
        return f;
    }

    float pdf(const glm::vec3& L) const {
        float NoL = glm::dot(mN, L);
        if (NoL <= 0.0f) return 0.0f;
        float p = (1.0f - mPSpec) * NoL / kPi;
        if (mPSpec > 0.0f) {
            glm::vec3 H = glm::normalize(mV + L);
            float NoH = std::max(glm::dot(mN, H), 0.0f);
            p += mPSpec * G1_GGX(mNoV, mS.alpha) * D_GGX(NoH, mS.alpha) / (4.0f * mNoV);
        }
        return p;
    }

    BSDFSample sample(PCG32& rng) const {
        BSDFSample s;
        float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        if (u0 < mPSpec) {
            // Visible-normal sampling of GGX (Heitz 2018) in the local frame (N = z).
            glm::vec3 v(glm::dot(mV, mT), glm::dot(mV, mB), glm::dot(mV, mN));
            float a = mS.alpha;
            glm::vec3 vh = glm::normalize(glm::vec3(a * v.x, a * v.y, std::max(v.z, 1e-4f)));
            float lensq = vh.x * vh.x + vh.y * vh.y;
            glm::vec3 t1 = lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1, 0, 0);
            glm::vec3 t2 = glm::cross(vh, t1);
            float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
            float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
            float sw = 0.5f * (1.0f + vh.z);
            p2 = (1.0f - sw) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + sw * p2;
            glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
            glm::vec3 h = glm::normalize(glm::vec3(a * nh.x, a * nh.y, std::max(0.0f, nh.z)));
            glm::vec3 H = h.x * mT + h.y * mB + h.z * mN;
            s.L = glm::reflect(-mV, H);
        } else {
            // Cosine-weighted hemisphere.
            float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
            float x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0f, 1.0f - u1));
            s.L = x * mT + y * mB + z * mN;
        }
        s.pdf = pdf(s.L);
        s.f = s.pdf > 0.0f ? eval(s.L) : glm::vec3(0.0f);
        return s;
    }

private:
    Surface mS;
    glm::vec3 mN, mV, mT, mB, mF0, mDiffuse;
    float mNoV, mPSpec;
};

float powerHeuristic(float a, float b) {
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

// The environment as a light: the latlong image and a 2D piecewise-constant distribution over
// its cells (a marginal CDF over rows, a conditional CDF per row) for next-event estimation.
// A cell's weight is the mean luminance of sampleEnvironment's bilinear lookup over the cell
// (taps 1/8, 3/4, 1/8 in u and in v, u wrapping and v clamped as the lookup does) times sin theta
// at the row's centre, so every cell the lookup can make bright has a weight. The density of a
// sample is computed from the same CDF entries it was drawn with: what is sampled is what the
// pdf says, whatever the rounding.
class EnvironmentLight {
public:
    explicit EnvironmentLight(EnvironmentImage img) : mImage(std::move(img)) {
        const int W = mImage.width, H = mImage.height;
        GI_ASSERT(W > 0 && H > 0 && mImage.rgb.size() == size_t(W) * size_t(H) * 3, "environment image size");
        std::vector<double> lum(size_t(W) * H), across(size_t(W) * H);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) lum[size_t(y) * W + x] = std::max(0.0f, luminance(mImage.texel(x, y)));
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const double* row = &lum[size_t(y) * W];
                across[size_t(y) * W + x] = 0.125 * row[(x + W - 1) % W] + 0.75 * row[x] + 0.125 * row[(x + 1) % W];
            }
        mColumnCdf.resize(size_t(H) * (W + 1));
        mRowCdf.resize(size_t(H) + 1);
        std::vector<double> rowSum(static_cast<size_t>(H), 0.0);
        std::vector<double> cdf(size_t(W) + 1);
        double total = 0.0;
        for (int y = 0; y < H; ++y) {
            const double* up = &across[size_t(std::max(y - 1, 0)) * W];
            const double* mid = &across[size_t(y) * W];
            const double* down = &across[size_t(std::min(y + 1, H - 1)) * W];
            double sinTheta = std::sin(double(kPi) * (y + 0.5) / H);
            cdf[0] = 0.0;
            for (int x = 0; x < W; ++x) cdf[size_t(x) + 1] = cdf[size_t(x)] + (0.125 * up[x] + 0.75 * mid[x] + 0.125 * down[x]) * sinTheta;
            rowSum[size_t(y)] = cdf[size_t(W)];
            float* out = &mColumnCdf[size_t(y) * (W + 1)];
            for (int x = 0; x <= W; ++x)
                out[x] = rowSum[size_t(y)] > 0.0 ? float(cdf[size_t(x)] / rowSum[size_t(y)]) : float(x) / float(W);
            out[W] = 1.0f;
            total += rowSum[size_t(y)];
        }
        mSampleable = total > 0.0;
        double acc = 0.0;
        mRowCdf[0] = 0.0f;
        for (int y = 0; y < H; ++y) {
            acc += rowSum[size_t(y)];
            mRowCdf[size_t(y) + 1] = mSampleable ? float(acc / total) : float(y + 1) / float(H);
        }
        mRowCdf[size_t(H)] = 1.0f;
    }

    const EnvironmentImage& image() const { return mImage; }

    // A direction drawn from two uniform numbers and its density in solid angle (0: no sample).
    float sample(float u0, float u1, float rotationDeg, glm::vec3& dir) const {
        if (!mSampleable) return 0.0f;
        const int W = mImage.width, H = mImage.height;
        float fy, fx;
        int y = pick(mRowCdf.data(), H, u0, fy);
        const float* columns = &mColumnCdf[size_t(y) * (W + 1)];
        int x = pick(columns, W, u1, fx);
        glm::vec2 uv((float(x) + fx) / float(W), (float(y) + fy) / float(H));
        float sinTheta = std::sin(kPi * uv.y);
        float pdfUV = (columns[x + 1] - columns[x]) * float(W) * (mRowCdf[size_t(y) + 1] - mRowCdf[size_t(y)]) * float(H);
        if (pdfUV <= 0.0f || sinTheta <= 0.0f) return 0.0f;
        dir = latLongDirection(uv, rotationDeg);
        return pdfUV / (2.0f * kPi * kPi * sinTheta);
    }

    // The density sample() draws direction `dir` with, in solid angle.
    float pdf(const glm::vec3& dir, float rotationDeg) const {
        if (!mSampleable) return 0.0f;
        const int W = mImage.width, H = mImage.height;
        glm::vec2 uv = latLongUV(dir, rotationDeg);
        int x = std::clamp(int(uv.x * float(W)), 0, W - 1), y = std::clamp(int(uv.y * float(H)), 0, H - 1);
        float sinTheta = std::sin(kPi * uv.y);
        if (sinTheta <= 0.0f) return 0.0f;
        const float* columns = &mColumnCdf[size_t(y) * (W + 1)];
        float pdfUV = (columns[x + 1] - columns[x]) * float(W) * (mRowCdf[size_t(y) + 1] - mRowCdf[size_t(y)]) * float(H);
        return pdfUV / (2.0f * kPi * kPi * sinTheta);
    }

private:
    // The entry i with cdf[i] <= u < cdf[i + 1] (never one of zero width) and where u lies in it.
    static int pick(const float* cdf, int n, float u, float& within) {
        int i = int(std::upper_bound(cdf, cdf + n + 1, u) - cdf) - 1;
        i = std::clamp(i, 0, n - 1);
        float width = cdf[i + 1] - cdf[i];
        within = width > 0.0f ? std::clamp((u - cdf[i]) / width, 0.0f, 0x1.fffffep-1f) : 0.5f;
        return i;
    }

    EnvironmentImage mImage;
    std::vector<float> mRowCdf;     // height + 1 entries, 0 to 1
    std::vector<float> mColumnCdf;  // per row, width + 1 entries, 0 to 1
    bool mSampleable = false;       // false for a black map
};

// The environment as one trace() sees it.
struct Environment {
    const EnvironmentLight* light = nullptr;  // null: no environment (black where rays escape)
    float intensity = 1.0f;
    float rotation = 0.0f;
    bool skybox = true;
    bool sampled = true;  // next-event estimation; off only through the test hook

    glm::vec3 radiance(const glm::vec3& d) const { return intensity * sampleEnvironment(light->image(), d, rotation); }
};

}  // namespace

struct PathTracer::Impl {
    Scene scene;  // a copy: the editor may load another scene while a reference renders
    RTCDevice device = nullptr;
    RTCScene rtc = nullptr;
    struct GeometryData {
        const Impl* impl;
        int draw;
    };
    std::vector<GeometryData> geometries;  // by Embree geometry ID
    // The emissive triangles as this frame's lights have them: each scene emitter's triangles
    // times its area light's colour x intensity (lights switched off are absent from the frame:
    // their triangles emit nothing, as in the raster), drawn by power for next-event estimation.
    struct EmissiveTriangle {
        int triangle;  // index into scene.indices / 3
        float area;
    };
    struct Emission {
        std::vector<glm::vec3> perTriangle;  // mean emitted radiance (the area light's), 0 where none
        std::vector<glm::vec3> scale;        // the area light's colour x intensity, 0 where none
        std::vector<EmissiveTriangle> triangles;
        std::vector<float> cdf;  // normalised, by power
        float power = 0.0f;      // sum of area * luminance
    };
    Emission emissionTable(const FrameSettings& fs) const {
        Emission e;
        e.perTriangle.assign(scene.triangleCount(), glm::vec3(0.0f));
        e.scale.assign(scene.triangleCount(), glm::vec3(0.0f));
        for (const LightSettings& l : fs.lights) {
            if (l.type != LightType::Area || l.emitter < 0 || size_t(l.emitter) >= scene.emitters.size()) continue;
            const gi::Emitter& em = scene.emitters[size_t(l.emitter)];
            for (size_t k = 0; k < em.triangles.size(); ++k) {
                int tri = int(em.triangles[k]);
                glm::vec3 Le = em.radiance[k] * emissionScale(l);
                if (luminance(Le) <= 0.0f) continue;
                const uint32_t* idx = &scene.indices[size_t(tri) * 3];
                glm::vec3 p0 = scene.vertices[idx[0]].position, p1 = scene.vertices[idx[1]].position,
                          p2 = scene.vertices[idx[2]].position;
                float area = 0.5f * glm::length(glm::cross(p1 - p0, p2 - p0));
                e.perTriangle[size_t(tri)] = Le;
                e.scale[size_t(tri)] = emissionScale(l);
                e.triangles.push_back({tri, area});
                e.power += area * luminance(Le);
                e.cdf.push_back(e.power);
            }
        }
        for (float& c : e.cdf) c /= e.power;
        return e;
    }
    std::vector<int> triangleMaterial;
    // The last environment loaded, keyed by its file, so passes of one render load it once.
    mutable std::mutex environmentMutex;
    mutable std::string environmentFile;
    mutable std::shared_ptr<const EnvironmentLight> environmentLight;

    std::shared_ptr<const EnvironmentLight> environment(const std::string& file, size_t budgetBytes) const {
        std::lock_guard<std::mutex> lock(environmentMutex);
        if (!environmentLight || environmentFile != file) {
            environmentLight = std::make_shared<const EnvironmentLight>(loadEnvironment(file, {}, budgetBytes));
            environmentFile = file;
        }
        return environmentLight;
    }

    // Interpolated texture coordinates (TEXCOORD_0, TEXCOORD_1) at barycentrics (u, v).
    std::pair<glm::vec2, glm::vec2> uvAt(int triangle, float u, float v) const {
        const uint32_t* idx = &scene.indices[size_t(triangle) * 3];
        const Vertex &a = scene.vertices[idx[0]], &b = scene.vertices[idx[1]], &c = scene.vertices[idx[2]];
        return {(1.0f - u - v) * a.uv + u * b.uv + v * c.uv, (1.0f - u - v) * a.uv1 + u * b.uv1 + v * c.uv1};
    }

    // A slot's texture of a material at a point, as common/material.glsl reads it.
    glm::vec4 sampleSlot(const Material& m, int slot, const std::pair<glm::vec2, glm::vec2>& uv) const {
        return sampleTexture(scene.textures[size_t(m.texture(slot))], m.uvTransform[slot].apply(uv.first, uv.second));
    }

    glm::vec4 baseColorAt(const Material& m, int triangle, float u, float v) const {
        glm::vec4 c = m.baseColor;
        if (m.baseColorTexture >= 0) c *= sampleSlot(m, kSlotBaseColor, uvAt(triangle, u, v));
        return c;
    }

    // Mask cuts below the cutoff; Blend is a stochastic mask, cut where alpha is below a
    // threshold hashed from the hit (so a ray sees through alpha of the surface, on average).
    static void alphaFilter(const RTCFilterFunctionNArguments* args) {
        const auto* g = static_cast<const GeometryData*>(args->geometryUserPtr);
        const Impl& impl = *g->impl;
        const Draw& d = impl.scene.draws[g->draw];
        const Material& m = impl.scene.materials[d.material];
        for (unsigned i = 0; i < args->N; ++i) {
            if (args->valid[i] != -1) continue;
            unsigned prim = RTCHitN_primID(args->hit, args->N, i);
            int tri = int(d.firstIndex / 3 + prim);
            float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
            float alpha = impl.baseColorAt(m, tri, u, v).a;
            float threshold = m.alphaCutoff;
            if (m.alphaMode == AlphaMode::Blend) {
                uint32_t ub, vb;
                std::memcpy(&ub, &u, 4);
                std::memcpy(&vb, &v, 4);
                uint64_t h = mix64((uint64_t(prim) << 32) ^ (uint64_t(ub) << 16) ^ uint64_t(vb) ^ (uint64_t(d.material) << 48));
                threshold = float(h >> 40) * 0x1p-24f * (1.0f - 1e-3f) + 1e-3f;
            }
            if (alpha < threshold) args->valid[i] = 0;
        }
    }

    explicit Impl(const Scene& s) : scene(s) {
        device = rtcNewDevice(nullptr);
        if (!device) throw Error("Embree: cannot create a device");
        rtc = rtcNewScene(device);
        rtcSetSceneBuildQuality(rtc, RTC_BUILD_QUALITY_HIGH);
        geometries.reserve(scene.draws.size());
        triangleMaterial.assign(scene.triangleCount(), 0);
        for (size_t di = 0; di < scene.draws.size(); ++di) {
            const Draw& d = scene.draws[di];
            const Material& m = scene.materials[d.material];
            RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            uint32_t triCount = d.indexCount / 3;
            // Each draw gets its own compact vertex list so Embree's buffers stay small.
            std::vector<uint32_t> used(scene.indices.begin() + d.firstIndex, scene.indices.begin() + d.firstIndex + d.indexCount);
            std::sort(used.begin(), used.end());
            used.erase(std::unique(used.begin(), used.end()), used.end());
            std::vector<uint32_t> local(d.indexCount);
            for (uint32_t k = 0; k < d.indexCount; ++k)
                local[k] = uint32_t(std::lower_bound(used.begin(), used.end(), scene.indices[d.firstIndex + k]) - used.begin());
            std::vector<glm::vec3> positions;
            for (uint32_t vi : used) positions.push_back(scene.vertices[vi].position);
            auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                    3 * sizeof(float), positions.size()));
            for (size_t k = 0; k < positions.size(); ++k) {
                vb[k * 3] = positions[k].x;
                vb[k * 3 + 1] = positions[k].y;
                vb[k * 3 + 2] = positions[k].z;
            }
            auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                       3 * sizeof(uint32_t), triCount));
            std::copy(local.begin(), local.end(), ib);
            geometries.push_back({this, int(di)});
            if (m.alphaMode != AlphaMode::Opaque) {
                rtcSetGeometryUserData(geom, &geometries.back());
                rtcSetGeometryIntersectFilterFunction(geom, alphaFilter);
                rtcSetGeometryOccludedFilterFunction(geom, alphaFilter);
            }
            rtcCommitGeometry(geom);
            unsigned id = rtcAttachGeometry(rtc, geom);
            GI_ASSERT(id == di, "Embree geometry IDs follow the draws");
            rtcReleaseGeometry(geom);
            for (uint32_t t = 0; t < triCount; ++t) triangleMaterial[d.firstIndex / 3 + t] = d.material;
        }
        rtcCommitScene(rtc);
    }

    ~Impl() {
        if (rtc) rtcReleaseScene(rtc);
        if (device) rtcReleaseDevice(device);
    }

    struct Hit {
        bool valid = false;
        float t = 0.0f;
        int triangle = 0;
        int material = 0;
        float u = 0.0f, v = 0.0f;
        glm::vec3 Ng{0.0f};
    };

    Hit intersect(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        rh.ray.org_x = o.x;
        rh.ray.org_y = o.y;
        rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x;
        rh.ray.dir_y = d.y;
        rh.ray.dir_z = d.z;
        rh.ray.tnear = tnear;
        rh.ray.tfar = tfar;
        rh.ray.mask = 0xFFFFFFFFu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(rtc, &ctx, &rh);
        Hit h;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
        const Draw& dr = scene.draws[rh.hit.geomID];
        h.valid = true;
        h.t = rh.ray.tfar;
        h.triangle = int(dr.firstIndex / 3 + rh.hit.primID);
        h.material = dr.material;
        h.u = rh.hit.u;
        h.v = rh.hit.v;
        h.Ng = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        return h;
    }

    bool occluded(const glm::vec3& o, const glm::vec3& d, float tfar) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRay r{};
        r.org_x = o.x;
        r.org_y = o.y;
        r.org_z = o.z;
        r.dir_x = d.x;
        r.dir_y = d.y;
        r.dir_z = d.z;
        r.tnear = 0.0f;
        r.tfar = tfar;
        r.mask = 0xFFFFFFFFu;
        rtcOccluded1(rtc, &ctx, &r);
        return r.tfar < 0.0f;
    }

    glm::vec3 shadingNormal(int triangle, float u, float v) const {
        const uint32_t* idx = &scene.indices[size_t(triangle) * 3];
        glm::vec3 n = (1.0f - u - v) * scene.vertices[idx[0]].normal + u * scene.vertices[idx[1]].normal +
                      v * scene.vertices[idx[2]].normal;
        float len = glm::length(n);
        return len > 0.0f ? n / len : glm::vec3(0, 1, 0);
    }

    // The shading normal N (already facing the viewer) bent by the material's normal map through
    // the interpolated tangent frame, as materialNormal() in common/material.glsl.
    glm::vec3 normalMapped(const Material& m, int triangle, float u, float v, const glm::vec3& N,
                           const std::pair<glm::vec2, glm::vec2>& uv) const {
        const uint32_t* idx = &scene.indices[size_t(triangle) * 3];
        const Vertex &a = scene.vertices[idx[0]], &b = scene.vertices[idx[1]], &c = scene.vertices[idx[2]];
        glm::vec4 tangent = (1.0f - u - v) * a.tangent + u * b.tangent + v * c.tangent;
        glm::vec3 t = glm::vec3(tangent) - N * glm::dot(N, glm::vec3(tangent));
        if (glm::dot(t, t) < 1e-12f) return N;
        t = glm::normalize(t);
        glm::vec3 bt = glm::cross(N, t) * (tangent.w < 0.0f ? -1.0f : 1.0f);
        glm::vec3 n = glm::vec3(sampleSlot(m, kSlotNormal, uv)) * 2.0f - 1.0f;
        n.x *= m.normalScale;
        n.y *= m.normalScale;
        glm::vec3 bent = t * n.x + bt * n.y + N * n.z;
        return glm::dot(bent, bent) > 1e-12f ? glm::normalize(bent) : N;
    }

    // Offset along the geometric normal, each coordinate by 16 float steps of itself (2^-19 of
    // it: the rounding of P = o + t d grows with each coordinate, so a floor at y = 0 far out
    // along x needs no more than one at the origin), plus a floor of 1e-5 of the scene's radius
    // for coordinates near zero. The floor was 1e-4 world units: a sizeable step in a room 2 cm
    // wide, which came out 14-17 % darker than the same room at 1 m
    // (Reference.TheImageIsTheSameAtAnyScale). The relative part was 1e-4 of the largest
    // coordinate (800 steps): half a metre for a room 5 km from the origin, whose shadow and
    // bounce rays then started that far off their surfaces (the room 3 % darker, the sphere's
    // shadow on the wall instead of the floor; Reference.TheImageIsTheSameFarFromTheOrigin).
    // 16 and 64 steps give the same Sponza, Cornell and basic references within 0.01 %.
    glm::vec3 margin(const glm::vec3& p) const { return 0x1p-19f * glm::abs(p) + glm::vec3(1e-5f * scene.bounds.radius()); }
    glm::vec3 offset(const glm::vec3& p, const glm::vec3& ng) const { return p + ng * margin(p); }

    // Light from one punctual light arriving at P along direction L (unoccluded): the light
    // model of the raster passes (common/light.h) on the same packed light. An area light is its
    // point with a cosine lobe (as the volumetric march sees it); surfaces sample its triangles.
    glm::vec3 punctual(const LightSettings& settings, const glm::vec3& P, glm::vec3& L, float& dist) const {
        const gi::Emitter* e = settings.type == LightType::Area && settings.emitter >= 0 &&
                                       size_t(settings.emitter) < scene.emitters.size()
                                   ? &scene.emitters[size_t(settings.emitter)]
                                   : nullptr;
        light::GPULight l = packLight(settings, e);
        glm::vec3 E(l.color);
        glm::vec3 dir(l.direction);
        if (l.info.x == shared::kLightDirectional) {
            L = -dir;
            dist = std::numeric_limits<float>::infinity();
            return E;
        }
        glm::vec3 toLight = glm::vec3(l.position) - P;
        dist = glm::length(toLight);
        L = toLight / std::max(dist, 1e-6f);
        return E * light::lightFalloff(l, dist, glm::dot(-L, dir));
    }

    // Radiance along the ray o + t d (t > tnear); `firstHit` gets the distance to the first
    // surface, infinity when the ray escapes.
    glm::vec3 radiance(glm::vec3 o, glm::vec3 d, float tnear, const FrameSettings& fs, const ReferenceSettings& rs,
                       const Environment& env, const Emission& em, PCG32& rng, uint64_t& rays, float& firstHit) const {
        const bool countDirect = rs.mode != ReferenceMode::Indirect;
        const bool countIndirect = rs.mode != ReferenceMode::Direct;
        glm::vec3 L(0.0f), beta(1.0f);
        float prevPdf = 0.0f;
        firstHit = std::numeric_limits<float>::infinity();
        for (int bounce = 0;; ++bounce) {
            Hit h = intersect(o, d, tnear, std::numeric_limits<float>::infinity());
            ++rays;
            if (!h.valid) {
                // The environment: seen by the camera only as the skybox; gathered by every later
                // ray, weighted against its next-event estimation as emission is.
                if (env.light) {
                    if (bounce == 0) {
                        if (env.skybox && countDirect) L += beta * env.radiance(d);
                    } else if (bounce <= 1 ? countDirect : countIndirect) {
                        float w = env.sampled ? powerHeuristic(prevPdf, env.light->pdf(d, env.rotation)) : 1.0f;
                        L += beta * env.radiance(d) * w;
                    }
                }
                break;
            }
            if (bounce == 0) firstHit = h.t;
            tnear = 0.0f;
            glm::vec3 P = o + d * h.t;
            const Material& m = scene.materials[h.material];
            glm::vec3 Ns = shadingNormal(h.triangle, h.u, h.v);
            glm::vec3 V = -d;

            std::pair<glm::vec2, glm::vec2> uv = uvAt(h.triangle, h.u, h.v);

            // Emission, on the side the shading normal points to (both sides when double-sided,
            // as the raster's G-buffer), times its area light's scale.
            const glm::vec3 Le = em.perTriangle[size_t(h.triangle)];
            if (luminance(Le) > 0.0f && (m.doubleSided || glm::dot(Ns, V) > 0.0f)) {
                bool counts = bounce <= 1 ? countDirect : countIndirect;
                if (counts) {
                    float w = 1.0f;
                    if (bounce > 0) {
                        float cosLight = std::abs(glm::dot(Ns, V));
                        float pdfLight = luminance(Le) / em.power * h.t * h.t / cosLight;
                        w = powerHeuristic(prevPdf, pdfLight);
                    }
                    L += beta * emission(scene, m, uv.first, uv.second) * em.scale[size_t(h.triangle)] * w;
                }
            }
            if (bounce >= rs.maxBounces) break;
            if (rs.mode == ReferenceMode::Direct && bounce >= 1) break;

            // Two-sided shading: normals face the incoming ray.
            glm::vec3 Ng = glm::dot(h.Ng, V) < 0.0f ? -h.Ng : h.Ng;
            if (glm::dot(Ns, Ng) < 0.0f) Ns = -Ns;
            // The material model of common/material.glsl: normal map, metallic-roughness texture.
            if (m.normalTexture >= 0) Ns = normalMapped(m, h.triangle, h.u, h.v, Ns, uv);
            glm::vec4 base = m.baseColor;
            if (m.baseColorTexture >= 0) base *= sampleSlot(m, kSlotBaseColor, uv);
            float roughness = m.roughness, metallic = m.metallic;
            if (m.metallicRoughnessTexture >= 0) {
                glm::vec4 mr = sampleSlot(m, kSlotMetallicRoughness, uv);
                roughness *= mr.g;
                metallic *= mr.b;
            }
            Surface s;
            s.baseColor = glm::vec3(base);
            s.metallic = metallic;
            s.alpha = std::max(roughness * roughness, 0.002f);
            s.specular = fs.render.specular;
            BSDF bsdf(s, Ns, V);
            glm::vec3 Po = offset(P, Ng);

            bool neeCounts = bounce == 0 ? countDirect : countIndirect;
            if (neeCounts) {
                for (const LightSettings& light : fs.lights) {
                    if (light.type == LightType::Area) continue;  // its triangles are sampled below
                    glm::vec3 Ldir;
                    float dist;
                    glm::vec3 E = punctual(light, P, Ldir, dist);
                    if (maxComponent(E) <= 0.0f) continue;
                    float NoL = glm::dot(Ns, Ldir);
                    if (NoL <= 0.0f || glm::dot(Ng, Ldir) <= 0.0f) continue;
                    glm::vec3 f = bsdf.eval(Ldir);
                    if (maxComponent(f) <= 0.0f) continue;
                    ++rays;
                    float tfar = std::isinf(dist) ? dist : dist * (1.0f - 1e-4f);
                    if (light.castShadows && occluded(Po, Ldir, tfar)) continue;
                    L += beta * f * NoL * E;
                }
                if (!em.triangles.empty()) L += beta * sampleEmitter(em, P, Po, Ns, Ng, bsdf, rng, rays);
                if (env.light && env.sampled) L += beta * sampleEnvironmentLight(env, Po, Ns, Ng, bsdf, rng, rays);
            }

            BSDFSample bs = bsdf.sample(rng);
            float NoL = glm::dot(Ns, bs.L);
            if (bs.pdf <= 0.0f || NoL <= 0.0f || glm::dot(Ng, bs.L) <= 0.0f) break;
            beta *= bs.f * NoL / bs.pdf;
            if (bounce + 1 >= rs.rouletteDepth) {
                float q = std::min(maxComponent(beta), 0.95f);
                if (rng.uniform() >= q) break;
                beta /= q;
            }
            prevPdf = bs.pdf;
            o = Po;
            d = bs.L;
        }
        return L;
    }

    // The camera ray's passage through the medium (gi/volumetric/medium.h): the radiance Ls
    // from the first surface on (hit at tHit, infinity for a miss) faded by T(eye, hit), plus
    // single scattering of each punctual light, one uniform distance per light on the lit part
    // of the ray inside the box. d is a unit vector.
    glm::vec3 throughMedium(const Medium& medium, const glm::vec3& eye, const glm::vec3& d, float tHit, const glm::vec3& Ls,
                            const FrameSettings& fs, const ReferenceSettings& rs, PCG32& rng, uint64_t& rays) const {
        float tEnter, tExit;
        if (!clipRayToBox(medium.box, eye, d, tHit, tEnter, tExit)) return Ls;
        glm::vec3 L = medium.attenuateScene ? Ls * medium.transmittance(tExit - tEnter) : Ls;
        // In-scattering is single scattering of direct light: not part of the indirect mode.
        if (rs.mode == ReferenceMode::Indirect) return L;
        for (const LightSettings& light : fs.lights) {
            float t0 = tEnter, t1 = tExit;
            if (!clipRayToLight(light, eye, d, t0, t1)) continue;
            float t = t0 + rng.uniform() * (t1 - t0);
            glm::vec3 x = eye + t * d;
            glm::vec3 Ldir;
            float dist;
            glm::vec3 Li = punctual(light, x, Ldir, dist);
            if (maxComponent(Li) <= 0.0f) continue;
            ++rays;
            float tfar = std::isinf(dist) ? dist : dist * (1.0f - 1e-4f);
            if (light.castShadows && occluded(x, Ldir, tfar)) continue;
            // theta lies between the light's direction of travel (-Ldir) and the way to the eye (-d).
            float cosTheta = glm::dot(Ldir, d);
            float Tlight = medium.transmittance(lightPathInBox(medium.box, light, x));
            float Tview = medium.transmittance(t - tEnter);
            float weight = medium.intensity * medium.sigmaS * float(phase(medium.phase, cosTheta)) * Tlight * Tview * (t1 - t0);
            L += weight * Li;
        }
        return L;
    }

    glm::vec3 sampleEmitter(const Emission& em, const glm::vec3& P, const glm::vec3& Po, const glm::vec3& Ns,
                            const glm::vec3& Ng, const BSDF& bsdf, PCG32& rng, uint64_t& rays) const {
        float u = rng.uniform();
        size_t i = size_t(std::lower_bound(em.cdf.begin(), em.cdf.end(), u) - em.cdf.begin());
        i = std::min(i, em.triangles.size() - 1);
        const EmissiveTriangle& e = em.triangles[i];
        const uint32_t* idx = &scene.indices[size_t(e.triangle) * 3];
        float su = std::sqrt(rng.uniform()), v = rng.uniform();
        float b1 = 1.0f - su, b2 = v * su;  // barycentrics of vertices 1 and 2 (Embree's u, v)
        glm::vec3 p0 = scene.vertices[idx[0]].position, p1 = scene.vertices[idx[1]].position, p2 = scene.vertices[idx[2]].position;
        glm::vec3 Pl = (1.0f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
        glm::vec3 Nl = shadingNormal(e.triangle, b1, b2);
        glm::vec3 toL = Pl - P;
        float dist2 = glm::dot(toL, toL);
        if (dist2 <= 0.0f) return glm::vec3(0.0f);
        float dist = std::sqrt(dist2);
        glm::vec3 Ldir = toL / dist;
        const Material& m = scene.materials[size_t(triangleMaterial[size_t(e.triangle)])];
        float cosLight = glm::dot(Nl, -Ldir);
        if (m.doubleSided) cosLight = std::abs(cosLight);
        float NoL = glm::dot(Ns, Ldir);
        if (cosLight <= 0.0f || NoL <= 0.0f || glm::dot(Ng, Ldir) <= 0.0f) return glm::vec3(0.0f);
        const glm::vec3 Le = em.perTriangle[size_t(e.triangle)];
        float pdfLight = luminance(Le) / em.power * dist2 / cosLight;
        glm::vec3 f = bsdf.eval(Ldir);
        if (maxComponent(f) <= 0.0f) return glm::vec3(0.0f);
        ++rays;
        // Stop short of the emitter's own triangle by the same margin the ray started with.
        if (occluded(Po, Ldir, dist * (1.0f - 1e-3f) - std::abs(glm::dot(Ldir, margin(Pl))))) return glm::vec3(0.0f);
        float w = powerHeuristic(pdfLight, bsdf.pdf(Ldir));
        auto uv = uvAt(e.triangle, b1, b2);
        return f * NoL * emission(scene, m, uv.first, uv.second) * em.scale[size_t(e.triangle)] * w / pdfLight;
    }

    // Next-event estimation of the environment: a direction drawn from its luminance, an
    // unbounded shadow ray, the power heuristic against BSDF sampling.
    glm::vec3 sampleEnvironmentLight(const Environment& env, const glm::vec3& Po, const glm::vec3& Ns, const glm::vec3& Ng,
                                     const BSDF& bsdf, PCG32& rng, uint64_t& rays) const {
        float u0 = rng.uniform(), u1 = rng.uniform();
        glm::vec3 Ldir;
        float pdfLight = env.light->sample(u0, u1, env.rotation, Ldir);
        if (pdfLight <= 0.0f) return glm::vec3(0.0f);
        float NoL = glm::dot(Ns, Ldir);
        if (NoL <= 0.0f || glm::dot(Ng, Ldir) <= 0.0f) return glm::vec3(0.0f);
        glm::vec3 f = bsdf.eval(Ldir);
        if (maxComponent(f) <= 0.0f) return glm::vec3(0.0f);
        glm::vec3 Le = env.radiance(Ldir);
        if (maxComponent(Le) <= 0.0f) return glm::vec3(0.0f);
        ++rays;
        if (occluded(Po, Ldir, std::numeric_limits<float>::infinity())) return glm::vec3(0.0f);
        float w = powerHeuristic(pdfLight, bsdf.pdf(Ldir));
        return f * NoL * Le * w / pdfLight;
    }
};

PathTracer::PathTracer(const Scene& scene) : mImpl(std::make_unique<Impl>(scene)) {}
PathTracer::~PathTracer() = default;

PathTracer::SurfaceHit PathTracer::nearestSurface(const glm::vec3& origin, const glm::vec3& dir, float tnear) const {
    Impl::Hit h = mImpl->intersect(origin, glm::normalize(dir), tnear, std::numeric_limits<float>::infinity());
    SurfaceHit s;
    if (!h.valid) return s;
    s.t = h.t;
    s.normal = mImpl->shadingNormal(h.triangle, h.u, h.v);
    return s;
}

bool PathTracer::trace(const FrameSettings& fs, const ReferenceSettings& rs, int firstSample, int count,
                       std::vector<double>& sum, const std::atomic<bool>* cancel) const {
    const int w = fs.width, h = fs.height;
    if (sum.empty()) sum.assign(size_t(w) * h * 3, 0.0);
    GI_ASSERT(sum.size() == size_t(w) * h * 3, "accumulation buffer size");
    // Rays leave the eye along directions from a camera moved to the origin: with the eye's
    // translation inside the inverted matrix, a camera 5 km out lost enough precision to shift
    // the picture by a fraction of a pixel (Reference.TheImageIsTheSameFarFromTheOrigin).
    CameraSettings atOrigin = fs.camera;
    atOrigin.target -= atOrigin.eye;
    atOrigin.eye = glm::vec3(0.0f);
    const glm::mat4 view = viewMatrix(atOrigin);
    const glm::mat4 invViewProj = glm::inverse(projectionMatrix(atOrigin, float(w) / float(h)) * view);
    const glm::vec3 forward = -glm::vec3(glm::inverse(view)[2]);
    const Medium medium = makeMedium(fs.volumetric, mImpl->scene.bounds);
    Environment env;
    std::shared_ptr<const EnvironmentLight> environment;
    if (fs.environment.enabled) {
        environment = mImpl->environment(fs.environment.file, fs.render.memoryBudgetBytes());  // throws naming the file
        // A map scaled to nothing lights nothing: the same image as no environment.
        if (fs.environment.intensity > 0.0f) env.light = environment.get();
        env.intensity = fs.environment.intensity;
        env.rotation = fs.environment.rotation;
        env.skybox = fs.environment.skybox;
        env.sampled = mEnvironmentSampling;
    }
    const Impl::Emission emission = mImpl->emissionTable(fs);
    std::atomic<bool> cancelled{false};
    tbb::parallel_for(tbb::blocked_range2d<int>(0, h, 16, 0, w, 16), [&](const tbb::blocked_range2d<int>& r) {
        if (cancel && cancel->load()) {
            cancelled = true;
            return;
        }
        uint64_t rays = 0;
        for (int y = r.rows().begin(); y < r.rows().end(); ++y)
            for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                size_t pixel = size_t(y) * w + x;
                glm::dvec3 acc(0.0);
                for (int s = firstSample; s < firstSample + count; ++s) {
                    PCG32 rng(mix64(pixel * 0x9E3779B97F4A7C15ULL + uint64_t(rs.seed)), uint64_t(s));
                    float jx = rng.uniform(), jy = rng.uniform();
                    glm::vec2 ndc(2.0f * (float(x) + jx) / float(w) - 1.0f, 1.0f - 2.0f * (float(y) + jy) / float(h));
                    glm::vec4 pn = invViewProj * glm::vec4(ndc, -1.0f, 1.0f);
                    glm::vec4 pf = invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
                    glm::vec3 dir = glm::normalize(glm::vec3(pf) / pf.w - glm::vec3(pn) / pn.w);
                    float tnear = fs.camera.near / std::max(glm::dot(dir, forward), 1e-4f);
                    float tHit;
                    glm::vec3 L = mImpl->radiance(fs.camera.eye, dir, tnear, fs, rs, env, emission, rng, rays, tHit);
                    // After the path, so the path's random numbers do not depend on the medium.
                    if (medium.active) L = mImpl->throughMedium(medium, fs.camera.eye, dir, tHit, L, fs, rs, rng, rays);
                    if (std::isfinite(L.x + L.y + L.z)) acc += glm::dvec3(L);
                }
                sum[pixel * 3] += acc.x;
                sum[pixel * 3 + 1] += acc.y;
                sum[pixel * 3 + 2] += acc.z;
            }
        mRays += rays;
    });
    return !cancelled;
}

ImageRGB PathTracer::render(const FrameSettings& fs, const ReferenceSettings& rs,
                                 const std::function<bool(int, int)>& progress) const {
    std::vector<double> sum;
    int done = 0;
    // Passes double in size so progress comes early and overhead stays small, up to 64 samples
    // per pixel, or fewer on a large image so a pass stays a few seconds long (progress is
    // reported per pass): at most kPassPixelSamples, rounded down to a power of two.
    constexpr double kPassPixelSamples = double(1 << 22);
    int maxPass = 64;
    while (maxPass > 1 && double(maxPass) * double(fs.width) * double(fs.height) > kPassPixelSamples) maxPass /= 2;
    int pass = 1;
    while (done < rs.spp) {
        int count = std::min(pass, rs.spp - done);
        trace(fs, rs, done, count, sum);
        done += count;
        pass = std::min(pass * 2, maxPass);
        if (progress && !progress(done, rs.spp)) break;
    }
    ImageRGB img;
    img.width = fs.width;
    img.height = fs.height;
    img.rgb.resize(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) img.rgb[i] = float(sum[i] / std::max(done, 1));
    return img;
}

}  // namespace gi
