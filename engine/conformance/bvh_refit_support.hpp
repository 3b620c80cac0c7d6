// bvh_refit_support.hpp: the GPU refit (shaders_glsl/bvh/refit.comp.glsl through render::recordRefit) against the
// CPU refit (bvh::refitBlas, flattened), every node bit for bit: shared by the registered check "bvh/refit"
// (bvh_refit_checks.cpp, asset-free meshes) and the asset-based refit test (tests/conformance/bvh/, the bunny).
#pragma once
#include <string>

#include "conformance/bvh_trace_support.hpp"
#include "conformance/conformance.hpp"

namespace idk::conformance {

// Uploads `moved` (same topology as t.mesh), refits on the GPU and compares every node with the CPU refit of the
// same BLAS; then t holds the moved mesh and the CPU-refit BLAS. Returns the number of differing nodes.
uint32_t expectExactRefit(vk::Context& ctx, vk::ShaderLibrary& shaders, Verdict& v, UploadedBlas& t,
                          const render::TriangleMesh& moved, const std::string& what);

// A smooth function of the position: shared vertices stay shared (the mesh stays closed).
render::TriangleMesh deformed(render::TriangleMesh mesh, float amplitude);

}  // namespace idk::conformance
