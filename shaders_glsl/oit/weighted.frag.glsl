#version 460
// weighted.frag.glsl: the weighted blended rung of order-independent transparency (McGuire & Bavoil 2013): the
// same forward shading as the sorted rung (transparency/forward_body.h), written to an additive accumulation and
// an additive -ln(1 - alpha) target in any order; oit/composite.comp resolves them over the lit image.
#extension GL_GOOGLE_include_directive : require
#define IDK_OIT_WEIGHTED
#include "../transparency/forward_body.h"
