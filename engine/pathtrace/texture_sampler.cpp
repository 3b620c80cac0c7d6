// texture_sampler.cpp: decoding scene textures for the CPU tracer and filtering them like the GPU sampler.
#include "pathtrace/texture_sampler.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <thread>

namespace idk::pathtrace {

namespace {

const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) t[size_t(i)] = float(scene::srgbToLinearD(i / 255.0));
        return t;
    }();
    return table;
}

// glTF wrap (10497 REPEAT, 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT) of integer texel coordinate i.
int wrapIndex(int i, int size, int mode) {
    if (mode == 33071) return std::clamp(i, 0, size - 1);
    if (mode == 33648) {
        const int period = 2 * size;
        int m = ((i % period) + period) % period;
        return m < size ? m : period - 1 - m;
    }
    return ((i % size) + size) % size;
}

glm::vec4 texel(const CpuTexture& t, int x, int y, bool srgb) {
    const uint8_t* p = &t.texels[(size_t(y) * t.width + size_t(x)) * 4];
    if (srgb) {
        const auto& lut = srgbTable();
        return glm::vec4(lut[p[0]], lut[p[1]], lut[p[2]], p[3] / 255.0f);
    }
    return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
}

}  // namespace

std::vector<CpuTexture> decodeSceneTextures(const scene::Scene& scene, std::vector<std::string>& warnings) {
    const std::vector<scene::TextureColorSpace> spaces = scene::textureColorSpaces(scene);
    std::vector<CpuTexture> out(scene.textures.size());
    std::vector<std::string> messages(scene.textures.size());
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i = next++; i < out.size(); i = next++) {
            CpuTexture& t = out[i];
            t.sampler = scene.textures[i].sampler;
            const auto& image = scene.textures[i].image;
            if (spaces[i] == scene::TextureColorSpace::Unused || !image || *image >= scene.images.size()) {
                t.width = t.height = 1;
                t.texels = {255, 255, 255, 255};
                continue;
            }
            const bool srgb = spaces[i] != scene::TextureColorSpace::Linear;
            scene::DecodedTexture d =
                scene::decodeImage(scene.images[*image], srgb, scene::imageLabel(scene, *image));
            if (d.placeholder && !d.reportedByLoader) messages[i] = d.warning;
            t.width = d.width;
            t.height = d.height;
            t.texels.assign(d.texels.begin(), d.texels.begin() + ptrdiff_t(d.mips.at(0).size));
            const scene::MipLevel& last = d.mips.back();
            const uint8_t* m = &d.texels[last.offset];
            t.mean = srgb ? glm::vec4(srgbTable()[m[0]], srgbTable()[m[1]], srgbTable()[m[2]], m[3] / 255.0f)
                          : glm::vec4(m[0], m[1], m[2], m[3]) / 255.0f;
        }
    };
    const unsigned threads = std::max(1u, std::min(std::thread::hardware_concurrency(), 8u));
    std::vector<std::thread> pool;
    for (unsigned k = 1; k < threads; ++k) pool.emplace_back(work);
    work();
    for (std::thread& th : pool) th.join();
    for (const std::string& m : messages)
        if (!m.empty()) warnings.push_back(m);
    return out;
}

glm::vec2 transformUv(const scene::TextureRef& ref, const glm::vec2& uv) {
    glm::vec3 row0, row1;
    textureTransformRows(ref, row0, row1);
    const glm::vec3 h(uv, 1.0f);
    return glm::vec2(glm::dot(row0, h), glm::dot(row1, h));
}

// The same rows as render/gpu_scene.cpp writes into GpuTextureSlot (R = [cos -sin; sin cos], the columns the
// extension's GLSL builds), so the CPU and GPU tracers and the raster transform alike.
void textureTransformRows(const scene::TextureRef& ref, glm::vec3& row0, glm::vec3& row1) {
    const float c = std::cos(ref.rotation), s = std::sin(ref.rotation);
    row0 = glm::vec3(c * ref.scale.x, -s * ref.scale.y, ref.offset.x);
    row1 = glm::vec3(s * ref.scale.x, c * ref.scale.y, ref.offset.y);
}

glm::vec4 sampleTexture(const CpuTexture& t, const glm::vec2& uv, bool srgb) {
    if (t.width == 0 || t.height == 0) return glm::vec4(1.0f);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return texel(t, 0, 0, srgb);
    const int w = int(t.width), h = int(t.height);
    const float x = uv.x * float(w), y = uv.y * float(h);
    if (t.sampler.magFilter == 9728) {  // NEAREST
        const auto fx = double(std::floor(x)), fy = double(std::floor(y));
        const int ix = int(std::fmod(fx, 1 << 24)), iy = int(std::fmod(fy, 1 << 24));
        return texel(t, wrapIndex(ix, w, t.sampler.wrapS), wrapIndex(iy, h, t.sampler.wrapT), srgb);
    }
    const float px = x - 0.5f, py = y - 0.5f;
    const float flx = std::floor(px), fly = std::floor(py);
    const float ax = px - flx, ay = py - fly;
    // Large coordinates are reduced first so the int conversion cannot overflow (repeat/mirror are periodic).
    const int x0 = int(std::fmod(double(flx), double(2 * w) * 4096.0));
    const int y0 = int(std::fmod(double(fly), double(2 * h) * 4096.0));
    const int xa = wrapIndex(x0, w, t.sampler.wrapS), xb = wrapIndex(x0 + 1, w, t.sampler.wrapS);
    const int ya = wrapIndex(y0, h, t.sampler.wrapT), yb = wrapIndex(y0 + 1, h, t.sampler.wrapT);
    const glm::vec4 top = glm::mix(texel(t, xa, ya, srgb), texel(t, xb, ya, srgb), ax);
    const glm::vec4 bottom = glm::mix(texel(t, xa, yb, srgb), texel(t, xb, yb, srgb), ax);
    return glm::mix(top, bottom, ay);
}

}  // namespace idk::pathtrace
