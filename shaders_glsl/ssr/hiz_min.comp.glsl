#version 460
// hiz_min.comp.glsl: one level of the CLOSEST-depth Hi-Z pyramid for the SSR march: the layout and push block of
// culling/hiz_build.comp.glsl (shared/depth_pyramid.h), the reduction min instead of max. Culling needs the
// farthest depth of a cell (an occluder hides a box only behind all of it); a ray march needs the nearest (a ray
// in front of the nearest surface of a cell passes the whole cell without hitting anything).
#extension GL_GOOGLE_include_directive : require
#define HIZ_REDUCE min  // the closest depth: the SSR march
#include "hiz_level.glsl"
