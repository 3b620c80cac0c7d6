// ui_types.h: the viewer's UI pass (engine/ui/ui_pass.cpp, shaders_glsl/ui/): Dear ImGui's vertex layout as the
// GPU reads it (vertex pulling by buffer device address) and the per-draw push constants.
#ifndef IDK_UI_TYPES_H
#define IDK_UI_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN
// Mirrors ImDrawVert (imgui.h): position in pixels, atlas UV, colour as packed RGBA8 (sRGB-encoded, R in the
// lowest byte). engine/ui/ui_pass.cpp asserts the two layouts agree.
struct UiVertex {
    vec2 position;
    vec2 uv;
    uint color;
};
IDK_GPU_SIZE(UiVertex, 20);

// clip = position * scale + translate maps ImGui's pixel space (y down) onto Vulkan clip space (y down).
struct UiPush {
    DeviceAddress vertices;  // UiVertex[], this frame's whole vertex stream
    vec2 scale;
    vec2 translate;
    uint textureIndex;  // bindless sampled index of the draw command's texture (the font atlas)
    uint samplerIndex;  // bindless sampler index
};
IDK_GPU_SIZE(UiPush, 32);
IDK_GPU_END

#endif
