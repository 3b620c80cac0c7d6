#version 460
// forward.vert.glsl: vertex pulling for the transmission pass, as transparency/forward.vert (each sorted command's
// firstInstance names its GpuInstance), with the pass's whole push block declared so the pipeline layout matches
// the fragment stage's (TransparencyPush, then TransmissionPush).
#extension GL_GOOGLE_include_directive : require
#include "scene_vertex.glsl"
#include "shadow_types.h"
#include "transmission_types.h"

layout(push_constant, scalar) uniform Push { TransparencyPush p; TransmissionPush tp; };

void main() { emitSceneVertex(uint(gl_InstanceIndex), p.instances, p.vertices, p.colors, p.uv1, p.frame); }
