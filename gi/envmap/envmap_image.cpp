#include "gi/envmap/envmap_image.h"

#include "common/shared.h"

#include "gi/render/image.h"
#include "gi/util/error.h"
#include "gi/util/paths.h"
#include "gi/util/png_layout.h"

#include <OpenImageIO/imageio.h>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>

namespace gi {

namespace {

using shared::kPi;

glm::vec3 rotateY(const glm::vec3& d, float deg) {
    float a = glm::radians(deg), c = std::cos(a), s = std::sin(a);
    return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

// OpenImageIO's messages may span lines; every error here is one line.
std::string oneLine(std::string text) {
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text.empty() ? "unknown error" : text;
}

// A map opened with its header read, no pixels yet: the header is checked (size, channels,
// kind) before any pixel buffer exists, so a file claiming 10^12 pixels is refused, not allocated.
struct OpenedImage {
    std::unique_ptr<OIIO::ImageInput> in;
    OIIO::ImageSpec spec;
    std::string name;  // the file, for messages
    int channels = 0;  // channels decoded: 3 (RGB) or 1 (grey, repeated)

    size_t pixels() const { return size_t(spec.width) * size_t(spec.height); }
    // Host bytes decoding takes: the decoded channels as floats plus the RGB copy kept.
    size_t decodeBytes() const { return pixels() * (size_t(channels) * 4 + 12); }
};

OpenedImage openImage(const std::filesystem::path& path) {
    OpenedImage img;
    img.name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(img.name + ": environment map is a folder, not an image file");
    if (std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) == 0 && !ec)
        throw Error(img.name + ": environment map is an empty file");
    if (std::string problem = pngFileLayoutProblem(path); !problem.empty())
        throw Error(img.name + ": environment map is damaged: " + problem);
    img.in = OIIO::ImageInput::open(img.name);
    if (!img.in) throw Error(img.name + ": cannot read environment map: " + oneLine(OIIO::geterror()));
    img.spec = img.in->spec();
    const OIIO::ImageSpec& spec = img.spec;
    if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1 || spec.depth < 1)
        throw Error(img.name + ": environment map has no pixels (header says " + std::to_string(spec.width) + "x" +
                    std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) + " channels)");
    if (spec.depth > 1 || spec.deep)
        throw Error(img.name + ": environment map is a " + std::string(spec.deep ? "deep" : "volume") + " image; expected a 2D image");
    if (spec.width > kMaxEnvironmentSide || spec.height > kMaxEnvironmentSide)
        throw Error(img.name + ": environment map of " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                    " is larger than " + std::to_string(kMaxEnvironmentSide) + " px per side (the largest texture GL 4.5 promises)");
    // RGB from the first three channels (OpenImageIO puts R, G, B first; alpha and any further
    // channels are ignored), grey (with or without alpha) from the first.
    img.channels = spec.nchannels >= 3 ? 3 : 1;
    return img;
}

void checkMemory(const std::string& name, const std::string& what, size_t bytes, size_t budgetBytes) {
    MemoryBudget(double(budgetBytes) / (1024.0 * 1024.0)).reserve(double(bytes), name + ": decoding the environment map (" + what + ")");
}

// Decodes an opened map as linear RGB, row 0 at the top.
EnvironmentImage decode(OpenedImage& file) {
    const OIIO::ImageSpec& spec = file.spec;
    std::vector<float> px(file.pixels() * size_t(file.channels));
    if (!file.in->read_image(0, 0, 0, file.channels, OIIO::TypeDesc::FLOAT, px.data()))
        throw Error(file.name + ": cannot decode environment map (truncated or damaged?): " + oneLine(file.in->geterror()));
    // Integer images are display-encoded unless tagged otherwise: 8-bit ones are taken as sRGB,
    // 16-bit ones only when OpenImageIO says so (linear 16-bit TIFFs are common).
    std::string space = spec.get_string_attribute("oiio:ColorSpace");
    bool srgb = (spec.format.basetype == OIIO::TypeDesc::UINT8 && space != "Linear" && space != "linear") ||
                (spec.format.basetype == OIIO::TypeDesc::UINT16 && (space == "sRGB" || space == "srgb"));
    EnvironmentImage img;
    img.width = spec.width;
    img.height = spec.height;
    img.source = file.name;
    img.rgb.resize(file.pixels() * 3);
    for (size_t i = 0; i < file.pixels(); ++i)
        for (int c = 0; c < 3; ++c) {
            // Grey images repeat channel 0.
            float v = px[i * size_t(file.channels) + size_t(file.channels == 3 ? c : 0)];
            if (!std::isfinite(v) || v < 0.0f) v = 0.0f;  // negative or NaN texels would poison the prefilter
            img.rgb[i * 3 + size_t(c)] = srgb ? srgbToLinear(v) : v;
        }
    file.in->close();
    return img;
}

// Reads any image OpenImageIO knows as linear RGB, row 0 at the top, refusing it from its header
// when decoding would take more than `budgetBytes`.
EnvironmentImage readImage(const std::filesystem::path& path, size_t budgetBytes) {
    OpenedImage file = openImage(path);
    if (file.spec.width < 2) throw Error(file.name + ": environment map is 1 px wide; a latlong map needs at least 2");
    checkMemory(file.name, std::to_string(file.spec.width) + "x" + std::to_string(file.spec.height) + " px", file.decodeBytes(),
                budgetBytes);
    return decode(file);
}

// The GL cube face and its (s, t) in [-1, 1] (t growing downwards in the face image) that a
// direction falls on; face order +X -X +Y -Y +Z -Z.
int faceOf(const glm::vec3& d, float& s, float& t) {
    glm::vec3 a = glm::abs(d);
    if (a.x >= a.y && a.x >= a.z) {
        s = d.x > 0 ? -d.z / a.x : d.z / a.x;
        t = -d.y / a.x;
        return d.x > 0 ? 0 : 1;
    }
    if (a.y >= a.z) {
        s = d.x / a.y;
        t = d.y > 0 ? d.z / a.y : -d.z / a.y;
        return d.y > 0 ? 2 : 3;
    }
    s = d.z > 0 ? d.x / a.z : -d.x / a.z;
    t = -d.y / a.z;
    return d.z > 0 ? 4 : 5;
}

EnvironmentImage loadCubeFaces(const std::string& pattern, const std::filesystem::path& presetFolder, size_t budgetBytes) {
    static const std::array<const char*, 6> names{"px", "nx", "py", "ny", "pz", "nz"};
    // Every face's header first: sizes agree and the whole cube fits the budget before any
    // pixel is decoded.
    std::array<OpenedImage, 6> files;
    size_t at = pattern.find("{face}");
    size_t bytes = 0;
    for (int f = 0; f < 6; ++f) {
        std::string name = pattern.substr(0, at) + names[size_t(f)] + pattern.substr(at + 6);
        OpenedImage& file = files[size_t(f)];
        file = openImage(resolveAsset(name, presetFolder));
        if (file.spec.width != file.spec.height || file.spec.width != files[0].spec.width)
            throw Error(file.name + ": cube faces must be square and of one size (" + names[0] + " is " +
                        std::to_string(files[0].spec.width) + "x" + std::to_string(files[0].spec.height) + ", this face " +
                        std::to_string(file.spec.width) + "x" + std::to_string(file.spec.height) + ")");
        bytes += file.decodeBytes();
    }
    const size_t side = size_t(files[0].spec.width);
    if (4 * side > size_t(kMaxEnvironmentSide))
        throw Error(files[0].name + ": cube faces of " + std::to_string(side) + " px make a latlong of " + std::to_string(4 * side) +
                    " px, larger than " + std::to_string(kMaxEnvironmentSide) + " px per side (the largest texture GL 4.5 promises)");
    checkMemory(pattern, "six faces of " + std::to_string(side) + "x" + std::to_string(side) + " px and their latlong", bytes + 8 * side * side * 12,
                budgetBytes);
    std::array<EnvironmentImage, 6> faces;
    for (int f = 0; f < 6; ++f) faces[size_t(f)] = decode(files[size_t(f)]);
    int n = faces[0].width;
    EnvironmentImage img;
    img.width = 4 * n;
    img.height = 2 * n;
    img.source = pattern;
    img.rgb.resize(size_t(img.width) * img.height * 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            glm::vec3 d = latLongDirection({(float(x) + 0.5f) / float(img.width), (float(y) + 0.5f) / float(img.height)}, 0.0f);
            float s, t;
            int f = faceOf(d, s, t);
            // Bilinear within the face (clamped at its edges).
            float fx = (s * 0.5f + 0.5f) * float(n) - 0.5f, fy = (t * 0.5f + 0.5f) * float(n) - 0.5f;
            int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
            float tx = fx - float(x0), ty = fy - float(y0);
            const EnvironmentImage& face = faces[size_t(f)];
            auto at = [&](int xx, int yy) { return face.texel(std::clamp(xx, 0, n - 1), std::clamp(yy, 0, n - 1)); };
            glm::vec3 c = glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), tx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
            for (int k = 0; k < 3; ++k) img.rgb[(size_t(y) * img.width + x) * 3 + size_t(k)] = c[k];
        }
    return img;
}

EnvironmentImage builtin(const std::string& name) {
    EnvironmentImage img;
    img.source = name;
    if (name == "builtin:constant") {
        img.width = 64;
        img.height = 32;
        img.rgb.assign(size_t(img.width) * img.height * 3, 1.0f);
        return img;
    }
    if (name != "builtin:sky")
        throw Error("key 'environment.file': unknown built-in '" + name + "' (valid: builtin:sky, builtin:constant)");
    img.width = 512;
    img.height = 256;
    img.rgb.resize(size_t(img.width) * img.height * 3);
    const glm::vec3 sun = glm::normalize(glm::vec3(0.6f, 0.5f, -0.62f));  // about 30 degrees up
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            glm::vec3 d = latLongDirection({(float(x) + 0.5f) / float(img.width), (float(y) + 0.5f) / float(img.height)}, 0.0f);
            glm::vec3 c;
            if (d.y >= 0.0f) {
                float h = std::pow(1.0f - d.y, 4.0f);
                c = glm::mix(glm::vec3(0.18f, 0.35f, 0.75f), glm::vec3(0.85f, 0.9f, 1.0f), h);
            } else {
                c = glm::mix(glm::vec3(0.35f, 0.3f, 0.25f), glm::vec3(0.15f, 0.13f, 0.11f), std::min(1.0f, -d.y * 3.0f));
            }
            // A soft sun: a 3 degree disc with a glow, bright enough to cast visible highlights.
            float cosAngle = glm::dot(d, sun);
            c += glm::vec3(1.0f, 0.9f, 0.75f) * (40.0f * glm::smoothstep(std::cos(glm::radians(3.0f)), std::cos(glm::radians(2.0f)), cosAngle) +
                                                 0.5f * std::pow(std::max(cosAngle, 0.0f), 64.0f));
            for (int k = 0; k < 3; ++k) img.rgb[(size_t(y) * img.width + x) * 3 + size_t(k)] = c[k];
        }
    return img;
}

}  // namespace

glm::vec2 latLongUV(const glm::vec3& dir, float rotationDeg) {
    if (!std::isfinite(dir.x + dir.y + dir.z + rotationDeg)) return {0.5f, 0.5f};  // no NaN reaches an index
    glm::vec3 d = rotateY(dir, -rotationDeg);
    return {0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi), std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi};
}

glm::vec3 latLongDirection(const glm::vec2& uv, float rotationDeg) {
    float phi = (uv.x - 0.5f) * 2.0f * kPi, theta = uv.y * kPi;
    glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
    return rotateY(d, rotationDeg);
}

std::array<float, 9> shBasis9(const glm::vec3& n) {
    return {0.282095f,
            0.488603f * n.y,
            0.488603f * n.z,
            0.488603f * n.x,
            1.092548f * n.x * n.y,
            1.092548f * n.y * n.z,
            0.315392f * (3.0f * n.z * n.z - 1.0f),
            1.092548f * n.x * n.z,
            0.546274f * (n.x * n.x - n.y * n.y)};
}

std::array<glm::vec3, 9> irradianceSH(const EnvironmentImage& env) {
    std::array<glm::dvec3, 9> sum{};
    double dPhi = 2.0 * kPi / env.width, dTheta = kPi / env.height;
    for (int y = 0; y < env.height; ++y) {
        double theta = (y + 0.5) * dTheta;
        double dOmega = std::sin(theta) * dPhi * dTheta;
        for (int x = 0; x < env.width; ++x) {
            glm::vec3 d = latLongDirection({(float(x) + 0.5f) / float(env.width), (float(y) + 0.5f) / float(env.height)}, 0.0f);
            std::array<float, 9> b = shBasis9(d);
            glm::dvec3 L(env.texel(x, y));
            for (int i = 0; i < 9; ++i) sum[size_t(i)] += L * double(b[size_t(i)]) * dOmega;
        }
    }
    // Clamped-cosine convolution per band (pi, 2 pi / 3, pi / 4), then / pi.
    const double band[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25};
    std::array<glm::vec3, 9> c;
    for (int i = 0; i < 9; ++i) c[size_t(i)] = glm::vec3(sum[size_t(i)] * band[i]);
    return c;
}

glm::vec3 sampleEnvironment(const EnvironmentImage& env, const glm::vec3& dir, float rotationDeg) {
    glm::vec2 uv = latLongUV(dir, rotationDeg);
    float fx = uv.x * float(env.width) - 0.5f, fy = uv.y * float(env.height) - 0.5f;
    int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
    float tx = fx - float(x0), ty = fy - float(y0);
    auto at = [&](int x, int y) {
        x = ((x % env.width) + env.width) % env.width;
        y = std::clamp(y, 0, env.height - 1);
        return env.texel(x, y);
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), tx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx), ty);
}

std::string resolveEnvironmentFile(const std::string& file, const std::filesystem::path& presetFolder) {
    if (file.empty()) throw Error("key 'environment.file': no environment map given");
    if (file.rfind("builtin:", 0) == 0) return file;
    size_t at = file.find("{face}");
    if (at == std::string::npos) return std::filesystem::absolute(resolveAsset(file, presetFolder)).string();
    // The folder the first face is found in holds the others.
    std::string first = file.substr(0, at) + "px" + file.substr(at + 6);
    std::filesystem::path found = std::filesystem::absolute(resolveAsset(first, presetFolder));
    std::string name = std::filesystem::path(file).filename().string();
    return (found.parent_path() / name).string();
}

EnvironmentImage loadEnvironment(const std::string& file, const std::filesystem::path& presetFolder, size_t budgetBytes) {
    if (file.empty()) throw Error("key 'environment.file': no environment map given");
    if (file.rfind("builtin:", 0) == 0) return builtin(file);
    if (file.find("{face}") != std::string::npos) return loadCubeFaces(file, presetFolder, budgetBytes);
    return readImage(resolveAsset(file, presetFolder), budgetBytes);
}

}  // namespace gi
