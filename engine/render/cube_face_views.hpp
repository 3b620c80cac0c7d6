// cube_face_views.hpp: the view-projection matrix of one point-shadow cube face, the matrix form of
// include/shadows.glsl's cubeFaceClip (face table, depth a + b / ma), so GPU culling (render/culling_math.hpp
// frustumView) can cull each face of a point light's cube like a camera view (frame/shadow_culling.hpp).
#pragma once
#include <glm/glm.hpp>

namespace idk::render {

// clip = M * (world, 1) equals cubeFaceClip(world - lightPosition, face, depth coefficients of near/far):
// x = sc, y = tc, z = a * ma + b, w = ma. Its frustum planes (x, y within +-w; ma in [near, far]) are the face's
// 90-degree pyramid from the light, cut at the cube's near and far planes.
glm::mat4 cubeFaceViewProjection(glm::vec3 lightPosition, uint32_t face, float nearPlane, float farPlane);

}  // namespace idk::render
