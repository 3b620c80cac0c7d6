#version 460
// forward.frag.glsl: the sorted ("over") rung of transparency: forward shading of BLEND materials, output
// (radiance, alpha) for back-to-front "over" blending (the body is in forward_body.h, shared with oit/weighted).
// Ports IDKEngine's RecordTransparent/fragment.glsl, sorted back to front instead of its k-buffer (reference 2.14).
#extension GL_GOOGLE_include_directive : require
#define IDK_FORWARD_VXGI  // inside the VXGI grid the fragments trace cones (forward_body.h)
#include "forward_body.h"
