// color.glsl: the sRGB transfer functions (IEC 61966-2-1), exact formulas. Used where 8-bit sRGB values are
// written or read by shader code rather than by the hardware (the G-buffer albedo, the tonemapped output).
#ifndef IDK_COLOR_GLSL
#define IDK_COLOR_GLSL

vec3 srgbEncode(vec3 linear) {
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

vec3 srgbDecode(vec3 encoded) {
    vec3 c = clamp(encoded, 0.0, 1.0);
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

#endif
