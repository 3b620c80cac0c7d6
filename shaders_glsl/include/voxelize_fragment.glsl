// voxelize_fragment.glsl: the fragment side of voxelization shared by the atomic rungs (voxelize_float.frag,
// voxelize_uint.frag, voxelize_record.frag) and the key pass before them (voxelize_key.frag, IDK_VOXELIZE_KEY_PASS):
// keeps a fragment only in the draw of its triangle's dominant axis (so each triangle is
// rasterized once, in the projection where it covers the most voxels), keeps only the front-most surface of each
// facing class in a voxel (shared/vxgi_depth_key.h: the key pass raises the voxel's key, the accumulating passes
// drop the fragments behind it before lighting them), evaluates the material and the radiance
// the surface leaves diffusely (every punctual light times its shadow: cube, cascades, spot map or a shadow ray; times
// albedo / pi, plus emission) on each side it radiates from, and finds its voxel. Ports IDKEngine's VXGI/Voxelize fragment shader, without its fudge terms (0.02 albedo ambient):
// the voxel holds exactly the outgoing diffuse radiance of first-bounce light, which the cone tracer gathers.
#ifndef IDK_VOXELIZE_FRAGMENT_GLSL
#define IDK_VOXELIZE_FRAGMENT_GLSL
#extension GL_EXT_nonuniform_qualifier : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "material_eval.glsl"
#include "pbr.glsl"
#include "shadows.glsl"
#include "light_shadows.glsl"
#include "rt_shadow_types.h"
#include "vxgi_types.h"
#include "voxel_images.glsl"
#include "voxelize_projection.glsl"
#include "voxelize_key.glsl"
// --shadows raytraced: shadow rays through the path tracer's BVH (the mask pass's traversal; our BVH on every
// rung: a GPU with VK_KHR_ray_query would trace these with it, as rt_shadows/mask_rq does).
#define WF_CUSTOM_PUSH
#include "../pathtrace/wf_stage_spec.h"
#include "../pathtrace/wf_trace.h"

layout(push_constant, scalar) uniform Push { VoxelizePush p; };

#ifndef IDK_VOXELIZE_KEY_PASS
#include "voxel_list.glsl"
// Appends the slab's voxel `local` (the accumulators' coordinates) to the draw's touched-voxel list, if it has one;
// called once per voxel and frame, by the fragment whose atomic found the voxel empty.
void appendTouchedVoxel(ivec3 local) {
    uint list = p.depthKeys >> kVoxelListShift;
    if (list == 0u) return;
    list -= 1u;
    uint slot = atomicAdd(gVoxelList[list].data[0], 1u);
    if (slot >= voxelListCapacity(list)) return;  // counted: the merge sees the overflow and visits every voxel
    uint z = uint(local.z) + voxelSlabZ(p.axis);
    gVoxelList[list].data[kVoxelListHeaderWords + slot] = packVoxelListEntry(uvec3(local.xy, z));
}
#endif

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec4 inTangent;
layout(location = 3) in vec2 inUv;
layout(location = 4) flat in uint inDraw;
layout(location = 5) in vec4 inColor;
layout(location = 6) in vec2 inUv1;
#ifdef IDK_VOXELIZE_DILATED
layout(location = 7) flat in vec4 inBounds;  // voxelize.geom's dilated triangle: its original NDC bounds + 1/2 pixel
#endif


float luminanceOf(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// Returns false when this fragment belongs to another draw or is cut away; else its voxel, radiance and facing
// (vxgi_types.h: the unit geometric normal of the side it radiates from, and the other side's share).
bool voxelFragment(out ivec3 voxel, out vec3 radiance, out vec4 facing) {
    // The triangle's plane from the world position's screen derivatives: exact for a triangle (its interpolants
    // are affine), taken before any discard so the whole quad is alive.
    vec3 geometric = cross(dFdx(inWorldPosition), dFdy(inWorldPosition));
    GpuInstance instance = InstanceBuffer(p.instances).data[inDraw];
    GpuMaterial m = MaterialBuffer(p.materials).data[nonuniformEXT(MeshBuffer(p.meshes).data[instance.mesh].material)];
    vec4 baseColor = m.baseColorFactor * sampleMaterialSlot(m.slots[kSlotBaseColor], inUv, inUv1) * inColor;
    vec4 mr = sampleMaterialSlot(m.slots[kSlotMetallicRoughness], inUv, inUv1);
    vec3 emissive = m.emissiveFactor * sampleMaterialSlot(m.slots[kSlotEmissive], inUv, inUv1).rgb;
    voxel = ivec3(0);
    radiance = vec3(0.0);
    facing = vec4(0.0);
    uint drawAxis = p.axis & kVoxelAxisMask;
    if (drawAxis <= 2u && dominantAxis(geometric) != drawAxis) return false;  // single draws: every fragment is its axis's
#ifdef IDK_VOXELIZE_DILATED
    // Keep a pixel only where its square overlaps the triangle's bounds: cuts the dilation's overshoot at sharp
    // corners. The viewport is the plain N x N one (no y flip), so NDC = pixel / N * 2 - 1.
    vec2 ndc = gl_FragCoord.xy / float(p.gridSize) * 2.0 - 1.0;
    if (any(lessThan(ndc, inBounds.xy)) || any(greaterThan(ndc, inBounds.zw))) return false;
#endif
    if (m.alphaMode == kAlphaMask && baseColor.a < m.alphaCutoff) return false;

    vec3 n = normalize(inNormal);
    vec3 g = normalize(geometric);
    if (dot(g, n) < 0.0) g = -g;  // the front's geometric normal
    vec3 t = (inWorldPosition - p.gridMin) / p.voxelSize;  // grid coordinates in voxels
    voxel = ivec3(floor(t));
    if (any(lessThan(voxel, ivec3(0))) || any(greaterThanEqual(voxel, ivec3(p.gridSize)))) return false;
    // The front-most rule's class and key, from the front side's normal: the same in the key pass and here without
    // any lighting (a double-sided surface's radiating side is known only after it).
    uint facingClass = voxelFacingClass(g);
    uint key = voxelDepthKey(t[facingClass >> 1u], voxel[facingClass >> 1u], facingClass);
    // This draw's z-slab: the fragment belongs to the one slab holding its integer voxel z (the key above is taken
    // in grid coordinates, so it is the same whatever the slab); from here on `voxel` addresses the slab's
    // accumulators and keys.
    int slabZ = int(voxelSlabZ(p.axis));
    int slabDepth = int(voxelSlabDepth(p.axis));
    if (voxel.z < slabZ || voxel.z >= slabZ + slabDepth) return false;
    voxel.z -= slabZ;
#ifdef IDK_VOXELIZE_KEY_PASS
    raiseVoxelKey(p.depthKeys & kVoxelListKeyMask, voxel, facingClass, key);
    return false;  // the key pass only raises keys
#else
    // Hidden behind a surface of its class in its voxel: dropped before its lights are evaluated (on a GPU this saves
    // the shadow lookups of hidden layers; lavapipe pays the same per fragment either way).
    if (!voxelFrontMost(p.depthKeys & kVoxelListKeyMask, voxel, facingClass, key)) return false;
    bool doubleSided = (m.flags & kMaterialDoubleSided) != 0u;
    vec3 diffuseAlbedo = baseColor.rgb * (1.0 - clamp(m.metallicFactor * mr.b, 0.0, 1.0)) / kPi;
    // The radiance leaving the front (normal n) and, for a double-sided surface, the back.
    vec3 front = vec3(0.0), back = vec3(0.0);
    if ((m.flags & kMaterialUnlit) != 0u) {
        front = baseColor.rgb;  // KHR_materials_unlit: the colour is the radiance
        back = doubleSided ? front : vec3(0.0);
    } else {
        GpuFrame f = FrameBuffer(p.frame).frame;
        LightBuffer lights = LightBuffer(f.lights);
        uint caster = 0u;  // render::shadowCasters: lights of nonzero intensity, in order
        for (uint i = 0; i < f.lightCount; ++i) {
            bool casts = any(greaterThan(lights.data[i].intensity, vec3(0.0)));
            bool rayShadowed = casts && caster < p.rayShadows;
            if (casts) ++caster;
            vec3 l;
            vec3 incident = lightIncidence(lights.data[i], inWorldPosition, l);
            // A double-sided surface is lit on whichever side faces the light; a single-sided one on its front.
            bool behind = doubleSided && dot(n, l) < 0.0;
            vec3 side = behind ? -n : n;
            float cosine = max(dot(side, l), 0.0);
            if (cosine <= 0.0) continue;
            float visibility = 1.0;
            if (rayShadowed) {
                // One hard shadow ray from the fragment (offset off its plane by the mask pass's relative 1e-4)
                // to the light; a sphere light's soft shadow is left to the screen-space mask.
                vec3 origin = inWorldPosition + side * (1e-4 * max(1.0, length(inWorldPosition)));
                bool directional = lights.data[i].type == kLightDirectional;
                float tMax = directional ? 1e30 : distance(origin, lights.data[i].position);
                GpuPtSceneDesc scene = WfSceneRef(p.pointShadows).d;
                uint salt = wfHash(floatBitsToUint(inWorldPosition.x) ^ wfHash(floatBitsToUint(inWorldPosition.z) + i));
                if (wfOccluded(scene, origin, l, tMax, salt)) visibility = 0.0;
            } else if (p.pointShadows != 0 && p.rayShadows == 0u) {
                GpuPointShadow s = PointShadowBuffer(p.pointShadows).data[i];
                // As shadeSurface: a light with maps (directional cascades, spot) stores its 2D-array index in
                // `cube`; ray-traced masks are per screen pixel and mean nothing here (such lights stay unshadowed).
                if (s.mapCount != 0u) visibility = mapShadowVisibility(p.pointShadows, s, inWorldPosition, side, l);
                else if (s.cube != kNoShadow && s.cube != kRayTracedShadow)
                    visibility = pointShadowVisibility(s, inWorldPosition, side, l);
            }
            vec3 c = diffuseAlbedo * incident * (cosine * visibility);
            if (behind) back += c;
            else front += c;
        }
        front += emissive;
        if (doubleSided) back += emissive;
    }
    front = max(front, vec3(0.0));  // never negative (the max rung's bit ordering needs it)
    back = max(back, vec3(0.0));
    // The voxel keeps the brighter side's radiance and normal, and the other side's share of it.
    float lf = luminanceOf(front), lb = luminanceOf(back);
    if (lb > lf) {
        radiance = back;
        facing = vec4(-g, lf / lb);
    } else {
        radiance = front;
        facing = vec4(g, lf > 0.0 ? lb / lf : (doubleSided ? 1.0 : 0.0));
    }
    return true;
#endif
}

#endif
