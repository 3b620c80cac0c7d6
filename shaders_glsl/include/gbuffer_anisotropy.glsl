// gbuffer_anisotropy.glsl: the KHR_materials_anisotropy direction in the G-buffer (the w word of the optional
// RGBA32UI layers target), written by gbuffer_fragment.glsl and read by deferred_lighting_pixel.glsl, so the deferred
// pass shades the anisotropic lobe in the frame the forward pass builds from its tangents. The direction lies in the
// tangent plane of the shading normal, so one angle suffices: measured in a basis that is a function of the
// normal alone (Duff et al. 2017), computed on both sides from the normal as the G-buffer stores it (octahedral
// snorm16, decoded before encoding), so writer and reader build the same basis even where it turns fast
// (n.z ~ 0). 16 bits of angle: 1e-4 rad. 0 means no direction (no tangent frame): the lighting pass then keeps the
// isotropic lobe at the rms roughness, as the forward pass does there.
#ifndef IDK_GBUFFER_ANISOTROPY_GLSL
#define IDK_GBUFFER_ANISOTROPY_GLSL

const float kAnisotropyAngleScale = 65534.0 / 6.28318530718;

void anisotropyBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// d: the anisotropy direction (world, any length); n: the stored (decoded) normal.
uint encodeAnisotropyDirection(vec3 d, vec3 n) {
    vec3 t, b;
    anisotropyBasis(n, t, b);
    vec2 p = vec2(dot(d, t), dot(d, b));
    if (!(dot(p, p) > 1e-12)) return 0u;
    float angle = atan(p.y, p.x) + 3.14159265359;  // [0, 2 pi]
    return 1u + min(uint(angle * kAnisotropyAngleScale + 0.5), 65534u);
}

vec3 decodeAnisotropyDirection(uint word, vec3 n) {
    if (word == 0u) return vec3(0.0);
    vec3 t, b;
    anisotropyBasis(n, t, b);
    float angle = float(word - 1u) / kAnisotropyAngleScale - 3.14159265359;
    return t * cos(angle) + b * sin(angle);
}

// The direction itself (unnormalised) from a tangent frame (t, b: glTF's tangent and bitangent): anisotropyTexture's
// RG remapped to [-1, 1] ((1, 0.5) without a texture: the tangent), turned by anisotropyRotation. The forward
// pass (material_layers.glsl's withAnisotropyFrame) and the G-buffer (gbuffer_fragment.glsl) share it.
vec3 anisotropyDirection(float rotation, vec3 t, vec3 b, vec2 textureRg) {
    vec2 d = textureRg * 2.0 - 1.0;
    float c = cos(rotation), sn = sin(rotation);
    return t * (c * d.x - sn * d.y) + b * (sn * d.x + c * d.y);
}

#endif
