// atmosphere_bake_test.cpp: the CPU single-scattering model (render/atmosphere.hpp atmosphereRadiance) behaves like
// a sky: a sunset is redder than noon towards the sun, a high sun gives a blue zenith, and the sky 3 degrees after
// sunset is dim. CPU only. The GPU bake against this model is the registered check "atmosphere/bake"
// (engine/conformance/atmosphere_checks.cpp).
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "render/atmosphere.hpp"

namespace idk::test {
namespace {

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

TEST(AtmosphereModel, SunsetIsRedderThanNoonAndTheSkyBelowTheHorizonIsDim) {
    auto colour = [&](float elevation, glm::dvec3 d) {
        return render::atmosphereRadiance(render::earthAtmosphere(render::sunDirection(elevation, 0.0f), 20.0f, 1, 1),
                                          glm::normalize(d), 32, 8);
    };
    glm::dvec3 towardsSun(0.0, 0.02, -1.0);
    glm::dvec3 noon = colour(60.0f, towardsSun), sunset = colour(1.0f, towardsSun);
    EXPECT_GT(sunset.r / sunset.b, 2.0 * noon.r / noon.b) << "long paths near the horizon scatter the blue out";
    EXPECT_GT(colour(60.0f, {0, 1, 0}).b, colour(60.0f, {0, 1, 0}).r) << "a high sun gives a blue zenith";
    EXPECT_LT(luminance(colour(-3.0f, {0, 1, 0})), 0.05 * luminance(colour(20.0f, {0, 1, 0})));
}

}  // namespace
}  // namespace idk::test
