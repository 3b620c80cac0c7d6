#version 460
// hiz_build.comp.glsl: one level of the Hi-Z depth pyramid (shared/depth_pyramid.h): each texel is the maximum of
// the 2 x 2 texels below it (the depth image's pixels for level 0; fewer at odd edges, none resampled). One
// invocation per texel; the portable compute rung (no sampler reduction mode needed). A real GPU would build
// several levels per dispatch from shared memory (as AMD's single-pass downsampler does); lavapipe gains nothing.
#extension GL_GOOGLE_include_directive : require
#define HIZ_REDUCE max  // the farthest depth: culling
#include "hiz_level.glsl"
