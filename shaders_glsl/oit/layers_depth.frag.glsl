#version 460
// layers_depth.frag.glsl: first pass of the fixed-layer OIT rung: each BLEND fragment that passes the opaque depth
// test inserts its depth into the pixel's sorted array of kOitLayerCount nearest depths (include/oit_layers.glsl), no
// shading and no attachments. The body's material fetch and discards are the shading pass's, so both passes agree
// on which fragments exist.
#extension GL_GOOGLE_include_directive : require
#define IDK_OIT_LAYER_DEPTHS
#include "../transparency/forward_body.h"
