#version 460
// upsample.comp.glsl: composites the reduced-resolution volumetric lighting into the full-resolution HDR image as
// hdr * transmittance + in-scattered radiance, upsampled depth-aware: the four nearest low-resolution samples with
// bilinear weights times a weight on how close each sample's ray length is to this pixel's (so fog does not bleed
// across depth edges); when no sample is close, the closest one alone. Ports IDKEngine's VolumetricLight/Upscale.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "volumetric_common.glsl"

layout(local_size_x = kVolumetricGroupSize, local_size_y = kVolumetricGroupSize) in;
layout(push_constant, scalar) uniform Push { VolumetricPush p; };

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(uvec2(pixel), f.extent))) return;
    vec3 dir;
    float len = volumetricLength(f, vec2(pixel) + 0.5, imageLoad(gImagesR32f[p.depth], pixel).r, p.maxDistance, dir);

    ivec2 size = imageSize(gImagesRgba16f[p.lowRes]);
    vec2 lowPos = (vec2(pixel) + 0.5) / float(p.scale) - 0.5;
    ivec2 base = ivec2(floor(lowPos));
    vec2 frac = lowPos - vec2(base);
    vec4 sum = vec4(0.0);
    float weight = 0.0, closest = 1e30;
    vec4 closestValue = vec4(0.0, 0.0, 0.0, 1.0);
    for (int j = 0; j <= 1; ++j) {
        for (int i = 0; i <= 1; ++i) {
            ivec2 q = clamp(base + ivec2(i, j), ivec2(0), size - 1);
            ivec2 qp = volumetricSamplePixel(q, p.scale, f.extent);
            vec3 qd;
            float qlen = volumetricLength(f, vec2(qp) + 0.5, imageLoad(gImagesR32f[p.depth], qp).r, p.maxDistance, qd);
            vec4 value = imageLoad(gImagesRgba16f[p.lowRes], q);
            float bilinear = (i == 0 ? 1.0 - frac.x : frac.x) * (j == 0 ? 1.0 - frac.y : frac.y);
            float rel = abs(qlen - len) / max(len, 1e-4);
            float w = bilinear * exp(-(rel * rel) / (0.05 * 0.05));  // 5% of the ray length: one surface
            sum += value * w;
            weight += w;
            if (rel < closest) {
                closest = rel;
                closestValue = value;
            }
        }
    }
    vec4 fog = weight > 1e-3 ? sum / weight : closestValue;
    vec4 hdr = imageLoad(gImagesRgba16f[p.target], pixel);
    imageStore(gImagesRgba16f[p.target], pixel, vec4(hdr.rgb * fog.a + fog.rgb, hdr.a));
}
