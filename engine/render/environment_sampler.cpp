#include "render/environment_sampler.h"

#include <algorithm>
#include <cmath>

#include "render/shader_math.h"

namespace vct {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Index i with cdf[i] ≤ u < cdf[i + 1], skipping empty intervals.
size_t findInterval(const double* cdf, size_t count, double u) {
    const double* it = std::upper_bound(cdf, cdf + count + 1, u);
    const size_t i = size_t(std::max<std::ptrdiff_t>(it - cdf - 1, 0));
    return std::min(i, count - 1);
}

}  // namespace

EnvironmentSampler::EnvironmentSampler(const EnvironmentMap& map) : map_(map) {
    const uint32_t w = map.width(), h = map.height();
    rowCdf_.assign(size_t(h) + 1, 0.0);
    columnCdf_.assign(size_t(h) * (w + 1), 0.0);
    for (uint32_t y = 0; y < h; ++y) {
        double* row = &columnCdf_[size_t(y) * (w + 1)];
        for (uint32_t x = 0; x < w; ++x) row[x + 1] = row[x] + double(glsl::luminance(map.texel(0, x, y)));
        const double rowSum = row[w];
        if (rowSum > 0.0)
            for (uint32_t x = 1; x <= w; ++x) row[x] /= rowSum;
        rowCdf_[y + 1] = rowCdf_[y] + rowSum * equirectTexelSolidAngle(y, w, h);
    }
    total_ = rowCdf_[h];
    if (total_ > 0.0)
        for (uint32_t y = 1; y <= h; ++y) rowCdf_[y] /= total_;
}

EnvironmentSampler::Sample EnvironmentSampler::sample(glm::vec2 u) const {
    Sample s;
    if (!(total_ > 0.0)) return s;
    const uint32_t w = map_.width(), h = map_.height();
    const size_t y = findInterval(rowCdf_.data(), h, double(u.y));
    const size_t x = findInterval(&columnCdf_[y * (w + 1)], w, double(u.x));
    // Reuse the fractions within the chosen intervals as uniform numbers inside the texel.
    const double* row = &columnCdf_[y * (w + 1)];
    const double fx = row[x + 1] > row[x] ? (double(u.x) - row[x]) / (row[x + 1] - row[x]) : 0.5;
    const double fy =
        rowCdf_[y + 1] > rowCdf_[y] ? (double(u.y) - rowCdf_[y]) / (rowCdf_[y + 1] - rowCdf_[y]) : 0.5;
    // Uniform in solid angle within the texel: cos θ uniform between the row's bounds.
    const double cos0 = std::cos(kPi * double(y) / h), cos1 = std::cos(kPi * double(y + 1) / h);
    const double cosTheta = cos0 + std::clamp(fy, 0.0, 1.0) * (cos1 - cos0);
    const float v = float(std::acos(std::clamp(cosTheta, -1.0, 1.0)) / kPi);
    const float uu = float((double(x) + std::clamp(fx, 0.0, 1.0)) / w);
    s.direction = glm::normalize(glsl::equirectDirection(glm::vec2(uu, v), map_.rotation));
    s.radiance = map_.texel(0, uint32_t(x), uint32_t(y));
    s.pdf = float(double(glsl::luminance(s.radiance)) / total_);
    return s;
}

float EnvironmentSampler::pdf(glm::vec3 dir) const {
    if (!(total_ > 0.0)) return 0.0f;
    return float(double(glsl::luminance(map_.radiance(dir))) / total_);
}

}  // namespace vct
