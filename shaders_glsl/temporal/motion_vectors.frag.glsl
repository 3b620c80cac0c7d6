#version 460
// motion_vectors.frag.glsl: writes (current uv - previous uv) of the fragment whose depth the G-buffer kept, so
// alpha-masked and back-face-rejected fragments (discarded by the G-buffer) never win here either. The pass has no
// depth attachment: the G-buffer depth decides. (On a real GPU this output would be one more G-buffer target; it
// is a separate pass here so the G-buffer stays untouched while the temporal passes are off.)
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "temporal_types.h"

layout(push_constant, scalar) uniform Push { MotionPush p; };

layout(location = 0) in vec4 inCurrent;
layout(location = 1) in vec4 inPrevious;
layout(location = 0) out uint outMotion;  // R32UI: packHalf2x16(current uv - previous uv)

void main() {
    float kept = imageLoad(gImagesR32f[p.depth], ivec2(gl_FragCoord.xy)).r;
    // The same vertex maths as the G-buffer; the tolerance absorbs interpolation differences between the two
    // pipelines (depth is 0 near .. 1 far, so near surfaces differ in the 7th digit at most).
    if (abs(gl_FragCoord.z - kept) > 1e-6 + 1e-6 * kept) discard;
    vec2 current = inCurrent.xy / inCurrent.w;
    vec2 previous = inPrevious.xy / inPrevious.w;
    outMotion = packHalf2x16((current - previous) * 0.5);  // NDC -> uv units (both axes point the same way)
}
