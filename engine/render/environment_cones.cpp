#include "render/environment_cones.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "render/shader_math.h"

namespace vct {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCapSlack = 1e-4;

// One level of the map with a running sum along each row, so that any run of columns (wrapping in azimuth)
// sums in two reads.
struct RowSums {
    uint32_t width = 0, height = 0;
    std::vector<glm::dvec3> prefix;  // per row width + 1 entries: prefix[i] = Σ of its first i texels

    RowSums(const EnvironmentMap& map, size_t level) : width(map.widths[level]), height(map.heights[level]) {
        prefix.resize(size_t(width + 1) * height, glm::dvec3(0.0));
        for (uint32_t y = 0; y < height; ++y)
            for (uint32_t x = 0; x < width; ++x)
                prefix[size_t(y) * (width + 1) + x + 1] =
                    prefix[size_t(y) * (width + 1) + x] + glm::dvec3(map.texel(level, x, y));
    }
    // Σ of `count` (≤ width) texels of row y from column `first` (any integer: taken modulo the width).
    glm::dvec3 run(uint32_t y, int64_t first, int64_t count) const {
        const glm::dvec3* row = &prefix[size_t(y) * (width + 1)];
        const int64_t a = ((first % width) + width) % width;
        if (a + count <= int64_t(width)) return row[a + count] - row[a];
        return (row[width] - row[a]) + row[a + count - width];
    }
};

// Mean radiance over the cap of half-angle `theta` about the direction of texel (x, y) of a width × height map,
// from `source` (its texel centres inside the cap, each weighted by its solid angle); none when no centre is
// inside. Rows are visited where the cap can reach them; in each, the cap covers the columns within ±Δφ of the
// texel's azimuth, from the spherical law of cosines: cos θ ≥ cos θ_y cos θ_r + sin θ_y sin θ_r cos Δφ.
std::optional<glm::vec3> capMean(const RowSums& source, uint32_t x, uint32_t y, uint32_t width,
                                 uint32_t height, double theta) {
    const double polar = kPi * (double(y) + 0.5) / double(height);
    const double azimuth = 2.0 * kPi * (double(x) + 0.5) / double(width) - kPi;
    // A hair wider than θ: the caps of layers 1, 2, … reach exactly 1, 2, … texels along a meridian, and the texel
    // centres there must not fall in or out by rounding.
    const double cosCap = std::cos(theta * (1.0 + kCapSlack));
    const double rows = double(source.height);
    const int64_t r0 = std::max<int64_t>(0, int64_t(std::floor((polar - theta) / kPi * rows - 0.5)));
    const int64_t r1 =
        std::min<int64_t>(source.height - 1, int64_t(std::ceil((polar + theta) / kPi * rows - 0.5)));
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (int64_t r = r0; r <= r1; ++r) {
        const double rowPolar = kPi * (double(r) + 0.5) / rows;
        const double c =
            (cosCap - std::cos(polar) * std::cos(rowPolar)) / (std::sin(polar) * std::sin(rowPolar));
        if (c > 1.0) continue;
        const double omega = equirectTexelSolidAngle(uint32_t(r), source.width, source.height);
        int64_t first = 0, count = source.width;
        if (c > -1.0) {
            const double halfWidth = std::acos(c);
            const double scale = double(source.width) / (2.0 * kPi);
            first = int64_t(std::ceil((azimuth - halfWidth + kPi) * scale - 0.5));
            count = std::min<int64_t>(
                int64_t(std::floor((azimuth + halfWidth + kPi) * scale - 0.5)) - first + 1, source.width);
            if (count <= 0) continue;
        }
        sum += omega * source.run(uint32_t(r), first, count);
        weight += omega * double(count);
    }
    if (weight <= 0.0) return std::nullopt;
    return glm::vec3(sum / weight);
}

}  // namespace

EnvironmentConeLayers environmentConeLayers(const EnvironmentMap& map) {
    EnvironmentConeLayers layers;
    // The first level no wider than kEnvironmentConeWidth: layer 0, and the size of every layer.
    size_t base = 0;
    while (base + 1 < map.levels.size() && map.widths[base] > kEnvironmentConeWidth) ++base;
    layers.width = map.widths[base];
    layers.height = map.heights[base];
    // Up to the cap of π (the whole sphere): 2^(count − 1) ≥ width.
    layers.count = 1;
    while ((1u << (layers.count - 1)) < layers.width) ++layers.count;
    layers.texels.resize(size_t(layers.width) * layers.height * layers.count);
    std::copy(map.levels[base].begin(), map.levels[base].end(), layers.texels.begin());

    for (uint32_t k = 1; k < layers.count; ++k) {
        const double theta = std::min(kPi * double(1u << k) / double(layers.width), kPi);
        // The coarsest level with a texel an eighth of the cap's radius or finer (2π/w ≤ θ/8), or level 0: within
        // 2 % of the cap's mean over level 0 (EnvironmentCones.EachLayerHoldsTheCapMeanOfTheMap).
        size_t level = 0;
        while (level + 1 < map.levels.size() && 2.0 * kPi / double(map.widths[level + 1]) <= theta / 8.0 &&
               map.heights[level + 1] > 1)
            ++level;
        const RowSums source(map, level);
        for (uint32_t y = 0; y < layers.height; ++y)
            for (uint32_t x = 0; x < layers.width; ++x) {
                // No texel centre inside the cap (not met at these sizes): the texel itself.
                layers.texels[(size_t(k) * layers.height + y) * layers.width + x] =
                    capMean(source, x, y, layers.width, layers.height, theta).value_or(map.texel(base, x, y));
            }
    }
    return layers;
}

glm::vec3 sampleEnvironmentCone(const EnvironmentConeLayers& layers, glm::vec3 dir, float tanHalfAngle,
                                float rotation) {
    const glm::vec2 uv = glsl::equirectUv(dir, rotation);
    const float layer =
        std::min(glsl::environmentMip(tanHalfAngle, float(layers.width)), float(layers.count - 1));
    const float x = uv.x * float(layers.width) - 0.5f, y = uv.y * float(layers.height) - 0.5f;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y)), k0 = int(std::floor(layer));
    const float fx = x - float(x0), fy = y - float(y0), fk = layer - float(k0);
    auto at = [&](int k, int xi, int yi) {
        const int w = int(layers.width), h = int(layers.height);
        return layers.texel(uint32_t(std::clamp(k, 0, int(layers.count) - 1)), uint32_t(((xi % w) + w) % w),
                            uint32_t(std::clamp(yi, 0, h - 1)));
    };
    auto bilinear = [&](int k) {
        return glm::mix(glm::mix(at(k, x0, y0), at(k, x0 + 1, y0), fx),
                        glm::mix(at(k, x0, y0 + 1), at(k, x0 + 1, y0 + 1), fx), fy);
    };
    return glm::mix(bilinear(k0), bilinear(k0 + 1), fk);
}

}  // namespace vct
