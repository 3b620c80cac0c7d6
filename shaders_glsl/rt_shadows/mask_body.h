// mask_body.h (GLSL include): body of rt_shadows/mask_bvh and mask_rq.comp.glsl (the rung is chosen by
// PT_RAY_QUERY, as the path tracer's trace stages): one shadow ray per pixel and shadowed light through the path
// tracer's traversal (pathtrace/wf_trace.h: our BVH or VK_KHR_ray_query, alpha MASK cut, BLEND by coverage), from
// the G-buffer's reconstructed position, offset along its normal, to the light (point/spot: its position;
// directional: infinitely far against its direction). Writes 1 where nothing blocks the ray, else 0; with a light
// radius, point and spot lights are spheres and the mask is the visible fraction of the sphere (soft shadows).
// Ports IDKEngine's ShadowsRayTraced/compute.glsl (hard shadows: one ray towards the light's centre).
#define WF_CUSTOM_PUSH
#include "../pathtrace/wf_stage_spec.h"
#include "../pathtrace/wf_trace.h"
#include "scene_buffers.glsl"
#include "octahedral.glsl"
#include "rt_shadow_types.h"

layout(local_size_x = kRtShadowGroupSize, local_size_y = kRtShadowGroupSize) in;
layout(push_constant, scalar) uniform Push { RtShadowPush p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer RtMaskRef { float v[]; };

// Origin offset along the normal, relative to the distance from the camera: the reconstructed position carries
// the depth buffer's relative error (~1e-7 for D32 at these distances); 1e-4 of the distance clears it and the
// surface's own triangle at grazing angles without visible light leaking at contact.
const float kRtShadowOffset = 1e-4;

// Soft shadows of a sphere light (radius p.lightRadius): the fraction of the sphere's solid angle seen from the
// origin that is unoccluded, estimated with p.softRays directions uniform in its cone (cos theta uniform in
// [cos thetaMax, 1]), stratified in cos theta and rotated per pixel (Cranley-Patterson) so neighbouring pixels
// decorrelate; each ray ends on the sphere's near surface. Directions below the surface's horizon count as
// blocked. rt_shadows/denoise.comp then filters the estimate along the surfaces (spatially; no temporal
// accumulation: on a real GPU a few rays plus history reprojection would be cheaper still).
float sphereLightVisibility(GpuPtSceneDesc s, vec3 origin, vec3 n, vec3 centre, uint salt) {
    vec3 toCentre = centre - origin;
    float d = length(toCentre);
    float r = p.lightRadius;
    if (d <= r) return 1.0;  // inside the light
    vec3 w = toCentre / d;
    vec3 u = normalize(abs(w.x) > 0.9 ? cross(w, vec3(0.0, 1.0, 0.0)) : cross(w, vec3(1.0, 0.0, 0.0)));
    vec3 v = cross(w, u);
    float sinMax = r / d, cosMax = sqrt(max(1.0 - sinMax * sinMax, 0.0));
    float rot1 = float(wfHash(salt) >> 8) * (1.0 / 16777216.0);
    float rot2 = float(wfHash(salt ^ 0x68E31DA4u) >> 8) * (1.0 / 16777216.0);
    uint rays = max(p.softRays, 1u), visible = 0u;
    for (uint k = 0u; k < rays; ++k) {
        float u1 = fract(rot1 + (float(k) + 0.5) / float(rays));
        float u2 = fract(rot2 + float(k) * 0.6180339887);
        float cosT = 1.0 - u1 * (1.0 - cosMax), sinT = sqrt(max(1.0 - cosT * cosT, 0.0));
        float phi = 6.2831853 * u2;
        vec3 dir = u * (cos(phi) * sinT) + v * (sin(phi) * sinT) + w * cosT;
        if (dot(n, dir) <= 0.0) continue;
        float tSphere = d * cosT - sqrt(max(r * r - d * d * sinT * sinT, 0.0));  // the near intersection
        if (!wfOccluded(s, origin, dir, tSphere, wfHash(salt + k * 0x9E3779B9u))) ++visible;
    }
    return float(visible) / float(rays);
}

void main() {
    GpuFrame f = FrameBuffer(p.frame).frame;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uint slot = gl_GlobalInvocationID.z;
    if (any(greaterThanEqual(uvec2(pixel), f.extent)) || slot >= p.casterCount) return;
    uint index = (slot * f.extent.y + uint(pixel.y)) * f.extent.x + uint(pixel.x);
    RtMaskRef mask = RtMaskRef(p.mask);
    float depth = imageLoad(gImagesR32f[p.depth], pixel).r;
    if (depth >= 1.0) {  // sky: nothing is shaded there
        mask.v[index] = 1.0;
        return;
    }
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(f.extent) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, depth, 1.0);
    vec3 position = h.xyz / h.w;
    vec3 n = octDecode(unpackSnorm2x16(imageLoad(gImagesR32ui[p.normal], pixel).r));

    GpuLight light = LightBuffer(f.lights).data[p.casters[slot]];
    vec3 l;
    float tMax;
    if (light.type == kLightDirectional) {
        l = -light.direction;
        tMax = 1e30;
    } else {
        vec3 toLight = light.position - position;
        tMax = length(toLight);
        l = toLight / max(tMax, 1e-20);
    }
    if (dot(n, l) <= 0.0) {  // faces away: the BRDF term is zero anyway
        mask.v[index] = 0.0;
        return;
    }
    vec3 origin = position + n * (kRtShadowOffset * max(1.0, distance(position, f.cameraPosition)));
    if (light.type != kLightDirectional) tMax = distance(origin, light.position);
    GpuPtSceneDesc s = WfSceneRef(p.scene).d;
    uint salt = wfHash(uint(pixel.x) * 0x9E3779B9u ^ wfHash(uint(pixel.y) + slot * 7919u));
    if (p.lightRadius <= 0.0 || light.type == kLightDirectional) {
        mask.v[index] = wfOccluded(s, origin, l, tMax, salt) ? 0.0 : 1.0;
        return;
    }
    mask.v[index] = sphereLightVisibility(s, origin, n, light.position, salt);
}
