// flip.cpp: LDR-FLIP from the paper (see flip.hpp): colour pipeline (CSF filtering in YyCxCz, Hunt-adjusted
// L*a*b*, HyAB, compression to [0, 1]) and feature pipeline (edge and point detectors on the luminance), combined
// per pixel as colourError ^ (1 - featureError).
#include "app/flip.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace idk::app {

namespace {

constexpr double kPi = std::numbers::pi;
// Constants of the paper (section 4).
constexpr double kQc = 0.7;   // colour error exponent
constexpr double kQf = 0.5;   // feature error exponent
constexpr double kPc = 0.4;   // compression knee, as a fraction of the largest colour error
constexpr double kPt = 0.95;  // error value at the knee
constexpr double kFeatureWidth = 0.082;  // degrees: the edge/point detectors' Gaussian is sigma = 0.5 w ppd

// Linear sRGB (D65) <-> CIE XYZ.
glm::dvec3 rgbToXyz(const glm::dvec3& c) {
    return {0.4124564 * c.r + 0.3575761 * c.g + 0.1804375 * c.b, 0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b,
            0.0193339 * c.r + 0.1191920 * c.g + 0.9503041 * c.b};
}
glm::dvec3 xyzToRgb(const glm::dvec3& v) {
    return {3.2404542 * v.x - 1.5371385 * v.y - 0.4985314 * v.z, -0.9692660 * v.x + 1.8760108 * v.y + 0.0415560 * v.z,
            0.0556434 * v.x - 0.2040259 * v.y + 1.0572252 * v.z};
}
const glm::dvec3 kWhite = rgbToXyz(glm::dvec3(1.0));  // D65 reference white of linear sRGB

// YyCxCz: CIELAB with the cube root left out (linear in XYZ, so filtering there is meaningful).
glm::dvec3 xyzToYcc(const glm::dvec3& v) {
    const glm::dvec3 n = v / kWhite;
    return {116.0 * n.y - 16.0, 500.0 * (n.x - n.y), 200.0 * (n.y - n.z)};
}
glm::dvec3 yccToXyz(const glm::dvec3& c) {
    const double y = (c.x + 16.0) / 116.0;
    return glm::dvec3(c.y / 500.0 + y, y, y - c.z / 200.0) * kWhite;
}

glm::dvec3 xyzToLab(const glm::dvec3& v) {
    auto f = [](double t) {
        constexpr double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    };
    const glm::dvec3 n = v / kWhite;
    return {116.0 * f(n.y) - 16.0, 500.0 * (f(n.x) - f(n.y)), 200.0 * (f(n.y) - f(n.z))};
}

// Hunt effect: chroma appears weaker at low luminance.
glm::dvec3 hunt(const glm::dvec3& lab) { return {lab.x, 0.01 * lab.x * lab.y, 0.01 * lab.x * lab.z}; }
double hyab(const glm::dvec3& a, const glm::dvec3& b) {
    return std::abs(a.x - b.x) + std::hypot(a.y - b.y, a.z - b.z);
}

struct Plane {
    int width = 0, height = 0;
    std::vector<double> v;
    double at(int x, int y) const {  // clamp to the edge
        return v[size_t(std::clamp(y, 0, height - 1)) * width + size_t(std::clamp(x, 0, width - 1))];
    }
};

struct Kernel {
    int radius = 0;
    std::vector<double> w;  // (2r+1)^2, row-major
};

Plane convolve(const Plane& in, const Kernel& k) {
    Plane out{in.width, in.height, std::vector<double>(in.v.size())};
    const int r = k.radius, side = 2 * r + 1;
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            double sum = 0.0;
            for (int j = -r; j <= r; ++j)
                for (int i = -r; i <= r; ++i) sum += k.w[size_t(j + r) * side + size_t(i + r)] * in.at(x + i, y + j);
            out.v[size_t(y) * in.width + size_t(x)] = sum;
        }
    return out;
}

// The spatial CSF of one opponent channel: the inverse Fourier transform of a1 exp(-b1 f^2) + a2 exp(-b2 f^2)
// (f in cycles per degree), sampled in degrees and normalized to sum 1.
Kernel csfKernel(double a1, double b1, double a2, double b2, int radius, double ppd) {
    Kernel k{radius, {}};
    double sum = 0.0;
    for (int y = -radius; y <= radius; ++y)
        for (int x = -radius; x <= radius; ++x) {
            const double d2 = (double(x) * x + double(y) * y) / (ppd * ppd);
            const double v = a1 * std::sqrt(kPi / b1) * std::exp(-kPi * kPi * d2 / b1) +
                             a2 * std::sqrt(kPi / b2) * std::exp(-kPi * kPi * d2 / b2);
            k.w.push_back(v);
            sum += v;
        }
    for (double& v : k.w) v /= sum;
    return k;
}

// Derivatives of a Gaussian (edge: first, point: second) along x (transpose for y), scaled so the positive weights
// sum to 1 and the negative ones to -1.
Kernel featureKernel(bool second, double ppd, bool alongY) {
    const double sigma = 0.5 * kFeatureWidth * ppd;
    const int radius = int(std::ceil(3.0 * sigma));
    Kernel k{radius, {}};
    double positive = 0.0, negative = 0.0;
    for (int y = -radius; y <= radius; ++y)
        for (int x = -radius; x <= radius; ++x) {
            const double u = alongY ? y : x;
            const double g = std::exp(-(double(x) * x + double(y) * y) / (2.0 * sigma * sigma));
            const double v = second ? (u * u / (sigma * sigma) - 1.0) * g : -u * g;
            k.w.push_back(v);
            (v > 0 ? positive : negative) += v;
        }
    for (double& v : k.w) v = v > 0 ? v / positive : (v < 0 ? v / -negative : 0.0);
    return k;
}

// |(kx * p, ky * p)| per pixel.
std::vector<double> magnitude(const Plane& p, const Kernel& kx, const Kernel& ky) {
    const Plane gx = convolve(p, kx), gy = convolve(p, ky);
    std::vector<double> m(p.v.size());
    for (size_t i = 0; i < m.size(); ++i) m[i] = std::hypot(gx.v[i], gy.v[i]);
    return m;
}

struct Prepared {
    std::vector<glm::dvec3> lab;  // Hunt-adjusted L*a*b* of the CSF-filtered image
    std::vector<double> edges, points;
};

Prepared prepare(const core::ImageRgba32f& image, double ppd) {
    const int w = int(image.width), h = int(image.height);
    const size_t n = size_t(w) * size_t(h);
    Plane ycc[3], luminance{w, h, std::vector<double>(n)};
    for (Plane& p : ycc) p = Plane{w, h, std::vector<double>(n)};
    for (size_t i = 0; i < n; ++i) {
        glm::dvec3 rgb;
        for (int c = 0; c < 3; ++c) {
            const float v = image.pixels[4 * i + size_t(c)];
            rgb[c] = std::isfinite(v) ? std::clamp(double(v), 0.0, 1.0) : 0.0;
        }
        const glm::dvec3 xyz = rgbToXyz(rgb), c = xyzToYcc(xyz);
        for (int k = 0; k < 3; ++k) ycc[k].v[i] = c[k];
        luminance.v[i] = xyz.y / kWhite.y;  // (Yy + 16) / 116, in [0, 1]
    }
    // Channel CSFs of the paper: achromatic, red-green, blue-yellow; one kernel size for all (from the widest b).
    const int radius = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd));
    const Kernel csf[3] = {csfKernel(1.0, 0.0047, 0.0, 1e-5, radius, ppd), csfKernel(1.0, 0.0053, 0.0, 1e-5, radius, ppd),
                           csfKernel(34.1, 0.04, 13.5, 0.025, radius, ppd)};
    Plane filtered[3];
    for (int k = 0; k < 3; ++k) filtered[k] = convolve(ycc[k], csf[k]);
    Prepared out;
    out.lab.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 rgb = glm::clamp(xyzToRgb(yccToXyz({filtered[0].v[i], filtered[1].v[i], filtered[2].v[i]})),
                                          glm::dvec3(0.0), glm::dvec3(1.0));
        out.lab[i] = hunt(xyzToLab(rgbToXyz(rgb)));
    }
    out.edges = magnitude(luminance, featureKernel(false, ppd, false), featureKernel(false, ppd, true));
    out.points = magnitude(luminance, featureKernel(true, ppd, false), featureKernel(true, ppd, true));
    return out;
}

}  // namespace

FlipResult computeFlip(const core::ImageRgba32f& test, const core::ImageRgba32f& reference, double ppd) {
    if (test.width != reference.width || test.height != reference.height)
        throw std::invalid_argument("image sizes differ: " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                    " vs " + std::to_string(reference.width) + "x" + std::to_string(reference.height));
    if (!(ppd > 0.0)) throw std::invalid_argument("FLIP: pixels per degree must be > 0");
    const Prepared t = prepare(test, ppd), r = prepare(reference, ppd);
    // The largest colour difference: between Hunt-adjusted green and blue.
    const double cmax = std::pow(hyab(hunt(xyzToLab(rgbToXyz({0, 1, 0}))), hunt(xyzToLab(rgbToXyz({0, 0, 1})))), kQc);
    FlipResult result;
    result.error.resize(t.lab.size());
    double sum = 0.0;
    for (size_t i = 0; i < t.lab.size(); ++i) {
        const double colour = std::pow(hyab(t.lab[i], r.lab[i]), kQc);
        const double e = colour < kPc * cmax ? kPt / kPc * colour / cmax
                                             : kPt + (colour - kPc * cmax) / (cmax - kPc * cmax) * (1.0 - kPt);
        const double feature = std::pow(
            std::max(std::abs(t.edges[i] - r.edges[i]), std::abs(t.points[i] - r.points[i])) / std::numbers::sqrt2, kQf);
        const double flip = std::clamp(std::pow(std::min(e, 1.0), 1.0 - std::min(feature, 1.0)), 0.0, 1.0);
        result.error[i] = float(flip);
        sum += flip;
    }
    result.mean = result.error.empty() ? 0.0 : sum / double(result.error.size());
    return result;
}

}  // namespace idk::app
