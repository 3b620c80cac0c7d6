// vxgi_half_res.glsl: the full-resolution G-buffer pixel that half-resolution pixel `h` traces (layout:
// shared/vxgi_upsample_types.h); the cone trace and the upsample agree through this one function.
#ifndef IDK_VXGI_HALF_RES_GLSL
#define IDK_VXGI_HALF_RES_GLSL
#include "vxgi_upsample_types.h"

ivec2 vxgiHalfResSource(ivec2 h, uvec2 extent) {
    ivec2 o = ((h.x + h.y) & 1) == 0 ? ivec2(0) : ivec2(int(kVxgiHalfResOddOffset));
    return min(2 * h + o, ivec2(extent) - 1);
}

#endif
