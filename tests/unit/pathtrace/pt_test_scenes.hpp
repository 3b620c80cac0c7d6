// pt_test_scenes.hpp: small scenes built in code for the path tracer's unit tests (a UV sphere, quads, a
// material per object) and image helpers (mean, RMSE).
#pragma once
#include <glm/glm.hpp>

#include "core/image_file.hpp"
#include "scene/camera.hpp"
#include "scene/scene.hpp"

namespace idk::test {

scene::Primitive uvSphere(const glm::vec3& centre, float radius, uint32_t rings = 16, uint32_t segments = 32);
// Quad p0 p1 p2 p3 (counter-clockwise seen from the front), two triangles, normal = front face.
scene::Primitive quad(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3);

// Axis-aligned box, 12 triangles wound counter-clockwise seen from outside (outward normals, flat).
scene::Primitive box(const glm::vec3& lo, const glm::vec3& hi);

// Adds a mesh with one primitive, a node placing it at `world` and its instance; returns the instance index.
uint32_t addObject(scene::Scene& s, scene::Primitive prim, const scene::Material& material,
                   const glm::mat4& world = glm::mat4(1.0f));

scene::Material diffuse(const glm::vec3& color);  // metallic 0, roughness 1, IOR 1.5
scene::CameraView lookAt(const glm::vec3& eye, const glm::vec3& target, float yfov = 0.6f);

glm::dvec3 imageMean(const core::ImageRgba32f& image);
double imageRmse(const core::ImageRgba32f& a, const core::ImageRgba32f& b);  // over RGB
bool imageFinite(const core::ImageRgba32f& image);

}  // namespace idk::test
