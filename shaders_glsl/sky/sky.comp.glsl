#version 460
// sky.comp.glsl: writes the environment's radiance into every background pixel (depth == 1), looking up the
// equirectangular map along the pixel's view ray; alpha 0 marks sky (lighting writes 1), so the HDR/EXR output's
// alpha is the geometry coverage. Ports IDKEngine's SkyBox/{vertex,fragment}.glsl (a cube
// drawn with depth LEQUAL there; a compute pass over the depth buffer here).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "sky_pixel.glsl"  // shared with the hardware-VRS fragment pass
#include "vrs_rates.glsl"

layout(local_size_x = kLightingGroupSize, local_size_y = kLightingGroupSize) in;
layout(push_constant, scalar) uniform Push { SkyPush p; };

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!vrsAnchorOfInvocation(p.vrsRates, pixel)) return;  // software VRS: vrs/reconstruct.comp fills the rest
    if (any(greaterThanEqual(uvec2(pixel), f.extent))) return;
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    if (depth < 1.0) return;

    imageStore(gImagesRgba16f[p.target], pixel, vec4(skyPixelRadiance(f, pixel), 0.0));  // alpha 0: sky
}
