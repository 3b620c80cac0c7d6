#version 460
// layers_shade.frag.glsl: second pass of the fixed-layer OIT rung: the forward shading of transparency/forward_body.h,
// stored into the pixel's slot whose depth equals this fragment's (include/oit_layers.glsl); fragments not among the
// kOitLayerCount nearest find no slot and are dropped. oit/layers_resolve.comp composites the slots in order.
#extension GL_GOOGLE_include_directive : require
#define IDK_OIT_LAYERS
#include "../transparency/forward_body.h"
