// features.cpp: the capability-ladder table. Each ladder lists its rungs best-first; the first available one
// is chosen, except that a CPU device's ray query (lavapipe emulates it in software) yields to our BVH, and the
// user's --fallback / --rung LADDER=RUNG override the choice. The GL-interop rung needs both
// VK_KHR_external_memory_fd and an OpenGL context exposing the NV extension the pass uses; the context's start-up
// probe (gl/interop_probe.hpp) fills DeviceCapabilities' gl* fields, and its note is the reason shown here.
#include "vk/features.hpp"

#include <stdexcept>

namespace idk::vk {

const char* rungName(Rung rung) {
    switch (rung) {
        case Rung::Native: return "native";
        case Rung::GlInterop: return "gl-interop";
        case Rung::Fallback: return "fallback";
    }
    return "?";
}

std::optional<Rung> rungFromName(const std::string& name) {
    for (Rung r : {Rung::Native, Rung::GlInterop, Rung::Fallback})
        if (name == rungName(r)) return r;
    return std::nullopt;
}

namespace {

std::string missing(bool available, const char* what) { return available ? "" : std::string("device lacks ") + what; }

// A VRS hardware rung: available when the device has the mechanism and a texel size the classifier can tile by
// (vk/shading_rate.hpp); the note names the tile, or what is missing.
RungOption vrsHardwareOption(bool has, const char* extension, const char* feature, const ShadingRateTile& tile) {
    if (!has) return {Rung::Native, extension, false, std::string("device lacks ") + extension + " (" + feature + ")"};
    if (tile.size == 0) return {Rung::Native, extension, false, tile.error};
    const std::string t = std::to_string(tile.size);
    return {Rung::Native, extension, true, "fragment lighting + sky at " + t + "x" + t + " rate texels"};
}

// Why a GL-interop rung is unavailable (the probe's reason, or the GL extension the context lacks), or what
// it runs on when it is available.
std::string glNote(const DeviceCapabilities& c, bool extension, const char* name) {
    if (!c.glInterop) return c.glInteropNote;
    if (!extension) return std::string("the OpenGL context lacks ") + name;
    return c.glInteropNote;
}

// The single-draw voxelization's native rung: both NV extensions, a geometry stage and three viewports.
bool voxelPassthrough(const DeviceCapabilities& c) {
    return c.geometryShaderPassthroughNv && c.viewportSwizzleNv && c.geometryShader && c.multiViewport;
}

std::string voxelPassthroughNote(const DeviceCapabilities& c) {
    std::string lacks;
    auto need = [&](bool has, const char* what) {
        if (!has) lacks += (lacks.empty() ? "" : ", ") + std::string(what);
    };
    need(c.geometryShaderPassthroughNv, "VK_NV_geometry_shader_passthrough");
    need(c.viewportSwizzleNv, "VK_NV_viewport_swizzle");
    need(c.geometryShader, "geometryShader");
    need(c.multiViewport, "multiViewport");
    return lacks.empty() ? "" : "device lacks " + lacks;
}

// The table, rungs best first, nothing chosen yet.
std::vector<Ladder> ladderTable(const DeviceCapabilities& c) {
    auto ladder = [](const char* id, const char* feature, std::vector<RungOption> options) {
        return Ladder{id, feature, std::move(options), Rung::Fallback, {}, {}};
    };
    const bool glAtomicFloat = c.glInterop && c.glAtomicFloat;
    std::vector<Ladder> ladders;
    ladders.push_back(ladder("mesh-shading", "mesh shading",
        {{Rung::Native, "VK_EXT_mesh_shader", c.meshShaderExt, missing(c.meshShaderExt, "VK_EXT_mesh_shader")},
         {Rung::Fallback, "multi-draw-indirect with count", true, ""}}));
    ladders.push_back(ladder("vrs", "variable-rate shading",
        // The hardware rungs light and draw the sky in a fragment pass whose rates come from a rate image
        // (frame/vrs_hardware.cpp); the fallback shades in compute and reconstructs.
        {vrsHardwareOption(c.fragmentShadingRate, "VK_KHR_fragment_shading_rate", "attachmentFragmentShadingRate",
                           khrShadingRateTile(c.shadingRateAttachmentTexel)),
         vrsHardwareOption(c.shadingRateImageNv, "VK_NV_shading_rate_image", "shadingRateImage",
                           nvShadingRateTile(c.shadingRateTexelNv)),
         {Rung::Fallback, "compute-side coarse shading", true, ""}}));
    ladders.push_back(ladder("vxgi-atomics", "voxel radiance atomics (VXGI)",
        {{Rung::Native, "float32 image atomic add", c.imageFloat32AtomicAdd,
          missing(c.imageFloat32AtomicAdd, "shaderImageFloat32AtomicAdd")},
         // Fragments append records; GL adds them with float atomics on shared memory (passes/vxgi_gl_accumulate).
         {Rung::GlInterop, "fragment records + GL_NV_shader_atomic_float adds via GL_EXT_memory_object_fd",
          glAtomicFloat, glNote(c, c.glAtomicFloat, "GL_NV_shader_atomic_float")},
         {Rung::Fallback, "three r32ui images + merge", true, ""}}));
    ladders.push_back(ladder("vxgi-volume-format", "directional voxel volume formats (VXGI)",
        // The six directional mip chains (frame/voxel_volume.hpp): 5 instead of 8 bytes per voxel and level.
        {{Rung::Native, "B10G11R11_UFLOAT colour + R8_UNORM opacity", c.packedVoxelFormats,
          missing(c.packedVoxelFormats, "storage + filtered sampling of 3D B10G11R11_UFLOAT and R8_UNORM images")},
         {Rung::Fallback, "RGBA16F", true, ""}}));
    ladders.push_back(ladder("vxgi-gl-accumulate", "GL-interop voxel sums (VXGI)",
        // Consulted on vxgi-atomics' gl-interop rung (passes/vxgi_gl_accumulate.cpp): the GL program that adds the
        // fragments' records. Native: two f16vec4 atomics per record into RGBA16F images, then a resolve to the
        // sums; fallback: eight float atomics per record straight into the sums.
        {{Rung::Native, "GL_NV_shader_atomic_fp16_vector: f16vec4 image adds (RGBA16F) + resolve",
          c.glInterop && c.glAtomicFp16Vector, glNote(c, c.glAtomicFp16Vector, "GL_NV_shader_atomic_fp16_vector")},
         {Rung::Fallback, "GL_NV_shader_atomic_float: float buffer adds", glAtomicFloat,
          glNote(c, c.glAtomicFloat, "GL_NV_shader_atomic_float")}}));
    ladders.push_back(ladder("float-atomics", "float atomic add (splatting)",
        {{Rung::Native, "buffer float atomicAdd (VK_EXT_shader_atomic_float)", c.bufferFloat32AtomicAdd,
          missing(c.bufferFloat32AtomicAdd, "shaderBufferFloat32AtomicAdd")},
         {Rung::GlInterop, "GL_NV_shader_atomic_float via GL_EXT_memory_object_fd", glAtomicFloat,
          glNote(c, c.glAtomicFloat, "GL_NV_shader_atomic_float")},
         {Rung::Fallback, "uint compare-and-swap loop", true, ""}}));
    ladders.push_back(ladder("conservative-raster", "conservative rasterization (voxelization)",
        {{Rung::Native, "VK_EXT_conservative_rasterization", c.conservativeRasterization,
          missing(c.conservativeRasterization, "VK_EXT_conservative_rasterization")},
         {Rung::Fallback, "geometry-shader triangle dilation", c.geometryShader,
          missing(c.geometryShader, "geometryShader")}}));
    ladders.push_back(ladder("voxel-single-draw", "single-draw voxelization (each triangle's dominant axis)",
        // Consulted by --gi-voxel-draws single (passes/vxgi_voxelize.cpp). Native: a passthrough geometry shader
        // only picks a viewport per triangle and three swizzled viewports project it; fallback: a geometry shader
        // that re-emits each triangle projected. (The three-draw default needs neither.)
        {{Rung::Native, "VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle", voxelPassthrough(c),
          voxelPassthroughNote(c)},
         {Rung::Fallback, "geometry shader re-emits each triangle projected", c.geometryShader,
          missing(c.geometryShader, "geometryShader")}}));
    ladders.push_back(ladder("point-shadow-faces", "point-shadow cube faces",
        {{Rung::Native, "vertex-shader gl_Layer (one instanced draw)", c.shaderOutputLayer,
          missing(c.shaderOutputLayer, "shaderOutputLayer")},
         {Rung::Fallback, "six draws, one per face", true, ""}}));
    ladders.push_back(ladder("ray-traversal", "ray traversal",
        {{Rung::Native, "VK_KHR_ray_query", c.rayQuery, missing(c.rayQuery, "VK_KHR_ray_query")},
         {Rung::Fallback, "compute BVH traversal", true, ""}}));
    ladders.push_back(ladder("subgroup-arithmetic", "subgroup reductions",
        {{Rung::Native, "subgroupAdd / subgroupMax", c.subgroupArithmetic,
          missing(c.subgroupArithmetic, "compute-stage subgroup arithmetic")},
         {Rung::Fallback, "shared-memory tree", true, ""}}));
    ladders.push_back(ladder("hiz-reduction", "Hi-Z pyramid reduction (GPU culling)",
        {{Rung::Native, "sampler MAX reduction (VK_EXT_sampler_filter_minmax)", c.samplerFilterMinmax,
          missing(c.samplerFilterMinmax, "samplerFilterMinmax with R32F MINMAX filtering")},
         {Rung::Fallback, "compute max of 2x2 loads", true, ""}}));
    return ladders;
}

void take(Ladder& ladder, const RungOption& option, std::string reason) {
    ladder.chosen = option.rung;
    ladder.chosenMechanism = option.mechanism;
    ladder.reason = std::move(reason);
}

// The first available rung (the last one when none is, so there is always a choice); the reason names what the
// better rungs lack.
void chooseBest(Ladder& ladder, const DeviceCapabilities& c) {
    std::string lacks;
    for (const RungOption& option : ladder.options) {
        const bool isLast = &option == &ladder.options.back();
        if (option.available || isLast) {
            take(ladder, option, lacks.empty() ? "best rung the device has" : lacks);
            if (!option.available) ladder.reason += "; " + option.note + " (taken anyway: last rung)";
            break;
        }
        lacks += (lacks.empty() ? "" : "; ") + option.note;
    }
    // Lavapipe's ray query walks its acceleration structures in emulated shader code: measured 53x slower than
    // our BVH on TransmissionTest (0.8x on the Cornell box and DamagedHelmet, BENCHMARKS.md "our BVH / ray
    // query"). A real GPU's native ray query is hardware and keeps the native rung.
    if (ladder.id == "ray-traversal" && c.cpuDevice && ladder.chosen == Rung::Native) {
        take(ladder, ladder.options.back(),
             "CPU device: its ray query is software; our BVH was 53x faster on TransmissionTest "
             "(BENCHMARKS.md, our BVH / ray query)");
    }
}

}  // namespace

std::vector<Ladder> buildLadders(const DeviceCapabilities& caps, const LadderChoice& choice, std::string* error) {
    std::vector<Ladder> ladders = ladderTable(caps);
    for (Ladder& ladder : ladders) {
        chooseBest(ladder, caps);
        if (choice.forceFallback && ladder.chosen != ladder.options.back().rung)
            take(ladder, ladder.options.back(), "--fallback: the portable rung");
    }
    for (const RungForce& force : choice.forced) {
        for (Ladder& ladder : ladders) {
            if (ladder.id != force.ladder) continue;
            const RungOption* option = nullptr;
            for (const RungOption& o : ladder.options)  // the first runnable option of that rung (vrs has two natives)
                if (o.rung == force.rung && (option == nullptr || (!option->available && o.available))) option = &o;
            const std::string spec = "--rung " + ladder.id + "=" + rungName(force.rung);
            if (option == nullptr || !option->available) {
                std::string runnable;
                for (const RungOption& o : ladder.options)
                    if (o.available) runnable += (runnable.empty() ? "" : "|") + std::string(rungName(o.rung));
                if (error && error->empty())
                    *error = spec + ": " + (option ? option->note : std::string("the ladder has no such rung")) +
                             " (rungs this device can run: " + ladder.id + "=" + runnable + ")";
                continue;
            }
            take(ladder, *option, "forced by " + spec);
        }
    }
    return ladders;
}

std::vector<std::string> ladderRungList() {
    std::vector<std::string> list;
    for (const Ladder& ladder : ladderTable(DeviceCapabilities{})) {
        std::string line = ladder.id + ": ";
        for (const RungOption& o : ladder.options) {
            if (&o != &ladder.options.front() && (&o - 1)->rung == o.rung) continue;  // vrs: two native mechanisms
            line += std::string(&o == &ladder.options.front() ? "" : "|") + rungName(o.rung);
        }
        list.push_back(line);
    }
    return list;
}

std::vector<Rung> ladderRungs(const std::string& ladderId) {
    for (const Ladder& ladder : ladderTable(DeviceCapabilities{})) {
        if (ladder.id != ladderId) continue;
        std::vector<Rung> rungs;
        for (const RungOption& o : ladder.options) rungs.push_back(o.rung);
        return rungs;
    }
    throw std::invalid_argument("unknown capability ladder '" + ladderId + "'");
}

RungForce parseRungForce(const std::string& spec) {
    auto invalid = [&](const std::string& why) {
        std::string names;
        for (const std::string& l : ladderRungList()) names += (names.empty() ? "" : ", ") + l;
        return std::invalid_argument("--rung '" + spec + "': " + why + " (give LADDER=RUNG; ladders and rungs: " +
                                     names + ")");
    };
    const size_t eq = spec.find('=');
    if (eq == std::string::npos) throw invalid("no '='");
    const std::string id = spec.substr(0, eq), rungText = spec.substr(eq + 1);
    for (const Ladder& ladder : ladderTable(DeviceCapabilities{})) {
        if (ladder.id != id) continue;
        const std::optional<Rung> rung = rungFromName(rungText);
        bool onLadder = false;
        for (const RungOption& o : ladder.options) onLadder = onLadder || (rung && o.rung == *rung);
        if (!onLadder) throw invalid("ladder '" + id + "' has no rung '" + rungText + "'");
        return RungForce{id, *rung};
    }
    throw invalid("unknown ladder '" + id + "'");
}

}  // namespace idk::vk
