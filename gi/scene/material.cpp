// The CPU side of the material model: texture transforms, bilinear texture lookups and emission,
// read by the path tracer and by anything that needs a material's value at a point.
#include "gi/render/image.h"
#include "gi/scene/scene.h"

#include <cmath>

namespace gi {

glm::vec3 TextureTransform::row(int r) const {
    float c = std::cos(rotation), s = std::sin(rotation);
    // KHR_texture_transform: translation * rotation * scale, rotation [c s; -s c].
    if (r == 0) return glm::vec3(c * scale.x, s * scale.y, offset.x);
    return glm::vec3(-s * scale.x, c * scale.y, offset.y);
}

glm::vec2 TextureTransform::apply(glm::vec2 uv0, glm::vec2 uv1) const {
    glm::vec3 uv(texCoord == 1 ? uv1 : uv0, 1.0f);
    return glm::vec2(glm::dot(row(0), uv), glm::dot(row(1), uv));
}

int Material::texture(int slot) const {
    switch (slot) {
        case kSlotBaseColor: return baseColorTexture;
        case kSlotMetallicRoughness: return metallicRoughnessTexture;
        case kSlotNormal: return normalTexture;
        case kSlotOcclusion: return occlusionTexture;
        case kSlotEmissive: return emissiveTexture;
    }
    return -1;
}

namespace {

struct SRGBTable {
    float v[256];
    SRGBTable() {
        for (int i = 0; i < 256; ++i) v[i] = srgbToLinear(float(i) / 255.0f);
    }
};

}  // namespace

glm::vec4 sampleTexture(const Texture& t, glm::vec2 uv) {
    static const SRGBTable srgb;
    float x = (uv.x - std::floor(uv.x)) * float(t.width) - 0.5f;
    float y = (uv.y - std::floor(uv.y)) * float(t.height) - 0.5f;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    float fx = x - float(x0), fy = y - float(y0);
    auto texel = [&](int xi, int yi) {
        xi = ((xi % t.width) + t.width) % t.width;
        yi = ((yi % t.height) + t.height) % t.height;
        const uint8_t* p = &t.rgba[(size_t(yi) * size_t(t.width) + size_t(xi)) * 4];
        if (t.srgb) return glm::vec4(srgb.v[p[0]], srgb.v[p[1]], srgb.v[p[2]], float(p[3]) / 255.0f);
        return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
    };
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), fx), glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

glm::vec3 emission(const Scene& scene, const Material& m, glm::vec2 uv0, glm::vec2 uv1) {
    glm::vec3 e = m.emissive;
    if (m.emissiveTexture >= 0 && size_t(m.emissiveTexture) < scene.textures.size())
        e *= glm::vec3(sampleTexture(scene.textures[size_t(m.emissiveTexture)], m.uvTransform[kSlotEmissive].apply(uv0, uv1)));
    return e;
}

}  // namespace gi
