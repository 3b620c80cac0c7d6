// cube_face_views.cpp: the cube-face matrices (see cube_face_views.hpp).
#include "render/cube_face_views.hpp"

namespace idk::render {

glm::mat4 cubeFaceViewProjection(glm::vec3 lightPosition, uint32_t face, float nearPlane, float farPlane) {
    // Rows sc, tc, ma of r = world - light (include/shadows.glsl cubeFaceClip, faces +X -X +Y -Y +Z -Z).
    static constexpr float kFaces[6][3][3] = {
        {{0, 0, -1}, {0, -1, 0}, {1, 0, 0}},  {{0, 0, 1}, {0, -1, 0}, {-1, 0, 0}},
        {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},
        {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}},   {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}},
    };
    const float (&f)[3][3] = kFaces[face % 6];
    const float a = farPlane / (farPlane - nearPlane), b = -nearPlane * a;  // pointShadowDepthCoefficients
    glm::mat4 m(0.0f);
    auto setRow = [&](int row, glm::vec3 n, float w) {  // clip[row] = dot(n, world - light) + w
        for (int c = 0; c < 3; ++c) m[c][row] = n[c];
        m[3][row] = w - glm::dot(n, lightPosition);
    };
    const glm::vec3 sc(f[0][0], f[0][1], f[0][2]), tc(f[1][0], f[1][1], f[1][2]), ma(f[2][0], f[2][1], f[2][2]);
    setRow(0, sc, 0.0f);
    setRow(1, tc, 0.0f);
    setRow(2, a * ma, b);
    setRow(3, ma, 0.0f);
    return m;
}

}  // namespace idk::render
