// wf_stage_spec.h (GLSL include): the specialization constants every tracing stage shares (shared/pt_wavefront.h
// ids) and the BVH stack sizes that include/bvh_traverse.glsl reads.
#ifndef IDK_WF_STAGE_SPEC_H
#define IDK_WF_STAGE_SPEC_H
#include "interop.h"
#include "pt_wavefront.h"
layout(constant_id = kSpecPtHasAlpha) const uint kPtHasAlpha = 0u;
layout(constant_id = kSpecPtNee) const uint kPtNee = 1u;
layout(constant_id = kSpecPtStackSize) const uint kPtStackSize = 32u;
layout(constant_id = kSpecPtTlasStackSize) const uint kPtTlasStackSize = 32u;
#define BVH_STACK_SIZE kPtStackSize
#define BVH_TLAS_STACK_SIZE kPtTlasStackSize
#define BVH_WIDE_STACK_SIZE kPtStackSize
#endif
