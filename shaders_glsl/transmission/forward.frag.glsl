#version 460
// forward.frag.glsl: the screen-space transmission pass (passes/transmission.cpp): transmissive (KHR_materials_
// transmission) materials forward-shaded after the opaque frame and the sky: the reflected lobes as the deferred
// pass shades them, plus the opaque colour seen through the surface (include/screen_transmission.glsl). The body is
// transparency/forward_body.h's, shared with the BLEND passes. Not in IDKEngine (its rasterizer has no transmission).
#extension GL_GOOGLE_include_directive : require
#define IDK_FORWARD_TRANSMISSION
#include "../transparency/forward_body.h"
