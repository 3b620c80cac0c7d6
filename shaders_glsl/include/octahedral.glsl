// octahedral.glsl: unit vectors <-> 2D octahedral coordinates in [-1, 1]^2 (Meyer et al. 2010, "On floating-point
// normal vectors"; Cigolle et al. 2014, JCGT 3(2)). The G-buffer stores normals this way, as IDKEngine's
// Compression.glsl does (it packs them into RG8; here RG16F).
#ifndef IDK_OCTAHEDRAL_GLSL
#define IDK_OCTAHEDRAL_GLSL

vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 octEncode(vec3 n) {
    vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z <= 0.0 ? (1.0 - abs(p.yx)) * signNotZero(p) : p;
}

vec3 octDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
    return normalize(n);
}

#endif
