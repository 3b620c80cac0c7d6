#version 460
// reconstruct.comp.glsl: the software VRS rung's second half. The lighting and sky passes shaded one anchor
// pixel per coarse cell (its top-left); every other pixel is interpolated here from the anchors of its cell and
// of the next cells right, down and diagonally (bilinear weights), each weighted by how well the anchor's
// G-buffer sample matches the pixel's: same kind (geometry or sky), normal agreement and relative view-depth
// difference. When no neighbour matches (an edge), the pixel's own cell anchor is taken. Anchors are never
// written, so reading and writing one image in one dispatch is race-free. No IDKEngine counterpart: there the
// hardware does coarse shading (NV_shading_rate_image) and replicates one fragment's colour over the cell.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "octahedral.glsl"
#include "vrs_rates.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant, scalar) uniform Push { VrsReconstructPush p; };

// View depth of a depth sample: clip w, the reciprocal of the unprojected point's w (one row of the inverse
// view-projection instead of a full unprojection: this pass runs for most pixels at coarse rates).
float viewDepth(GpuFrame f, uvec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    mat4 m = f.inverseViewProjection;
    return 1.0 / abs(dot(vec4(m[0][3], m[1][3], m[2][3], m[3][3]), vec4(ndc, depth, 1.0)));
}

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(pixel, f.extent))) return;
    if (p.fillSentinel != 0u) {  // test hook: marks every pixel, so that the shaded ones can be counted
        imageStore(gImagesRgba16f[p.target], ivec2(pixel), vec4(kVrsSentinel));
        return;
    }
    VrsRatesRef r = VrsRatesRef(p.rates);
    uvec2 cell = vrsCellSize(vrsTileRate(r, pixel));
    uvec2 anchor = pixel / cell * cell;
    if (anchor == pixel) return;  // shaded by lighting or sky

    float depth = imageLoad(gImagesR32f[p.depth], ivec2(pixel)).r;
    bool sky = depth >= 1.0;
    vec3 n = sky ? vec3(0.0) : octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], ivec2(pixel)).r));
    float dist = sky ? 0.0 : viewDepth(f, pixel, depth);
    vec2 t = vec2(pixel - anchor) / vec2(cell);

    vec3 sum = vec3(0.0);
    float weightSum = 0.0;
    for (uint k = 0u; k < 4u; ++k) {
        uvec2 step = uvec2(k & 1u, k >> 1u);
        uvec2 a = anchor + step * cell;
        if (any(greaterThanEqual(a, f.extent)) || !vrsIsAnchor(r, a)) continue;
        float w = (step.x == 1u ? t.x : 1.0 - t.x) * (step.y == 1u ? t.y : 1.0 - t.y);
        float aDepth = imageLoad(gImagesR32f[p.depth], ivec2(a)).r;
        if ((aDepth >= 1.0) != sky) continue;
        if (!sky) {
            vec3 an = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], ivec2(a)).r));
            float agree = max(dot(n, an), 0.0);
            agree *= agree; agree *= agree; agree *= agree;  // cos^8: ~0.34 at 15 degrees
            float rel = abs(viewDepth(f, a, aDepth) - dist) / max(dist, 1e-6);
            w *= agree / (1.0 + 100.0 * rel);  // 1% farther: half weight
        }
        sum += w * imageLoad(gImagesRgba16f[p.target], ivec2(a)).rgb;
        weightSum += w;
    }
    vec3 color = weightSum > 1e-4 ? sum / weightSum : imageLoad(gImagesRgba16f[p.target], ivec2(anchor)).rgb;
    imageStore(gImagesRgba16f[p.target], ivec2(pixel), vec4(color, sky ? 0.0 : 1.0));  // alpha: coverage
}
