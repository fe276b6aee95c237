#include "app/cli/upsample_views.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "io/image_io.h"

namespace vct {

namespace {

std::vector<float> readWeightSum(Renderer& renderer) {
    if (!renderer.voxelGrid()) throw UsageError("the upsampling views need GI (drop --gi off)");
    if (renderer.settings().traceScale <= 1)
        throw UsageError("the upsampling views need a low-resolution trace (--trace-scale 2 or 4)");
    if (!renderer.settings().writeWeightSum)
        throw Error("the upsampling views need the sum of weights (RenderSettings::writeWeightSum)");
    return renderer.readFloatImage(renderer.targets().weightSum);
}

// A 5-stop ramp (black, blue, cyan, yellow, white) at t ∈ [0, 1].
glm::vec3 heat(float t) {
    static const glm::vec3 stops[] = {
        {0, 0, 0}, {0.1f, 0.2f, 1.0f}, {0, 0.9f, 0.9f}, {1.0f, 0.9f, 0}, {1, 1, 1}};
    t = std::clamp(std::isfinite(t) ? t : 0.0f, 0.0f, 1.0f) * 4.0f;
    const int i = std::min(int(t), 3);
    return glm::mix(stops[i], stops[i + 1], t - float(i));
}

}  // namespace

std::vector<uint8_t> resampleOverlay(Renderer& renderer) {
    const std::vector<float> weights = readWeightSum(renderer);
    std::vector<uint8_t> ldr = renderer.readLdr();
    for (size_t i = 0; i * 4 < ldr.size(); ++i) {
        if (weights[i * 4 + 2] < 0.5f) continue;
        ldr[i * 4 + 0] = 255;
        ldr[i * 4 + 1] = 0;
        ldr[i * 4 + 2] = 0;
    }
    return ldr;
}

std::vector<uint8_t> weightHeatMap(Renderer& renderer) {
    const std::vector<float> weights = readWeightSum(renderer);
    const std::vector<float> depth = renderer.readFloatImage(renderer.targets().depth);
    const float tau = resampleThreshold(renderer.settings());
    // Log scale with τ at a quarter of the ramp (blue) and A_max at the top (white); the image counts the
    // history in pixel-own samples (upsample.comp), so A_max is RenderSettings::historyCap there.
    const float lo = std::log2(tau) - 2.0f, hi = std::log2(renderer.settings().historyCap);
    std::vector<uint8_t> bytes(weights.size());
    for (size_t i = 0; i * 4 < bytes.size(); ++i) {
        glm::vec3 c(0.35f);
        if (depth[i * 4] < 1.0f) {
            const float w = std::min(weights[i * 4], weights[i * 4 + 1]);
            c = w > 0.0f ? heat((std::log2(w) - lo) / (hi - lo)) : glm::vec3(0.0f);
        }
        for (int k = 0; k < 3; ++k) bytes[i * 4 + size_t(k)] = uint8_t(std::lround(c[k] * 255.0f));
        bytes[i * 4 + 3] = 255;
    }
    return bytes;
}

std::vector<std::string> writeUpsampleAux(Renderer& renderer, const std::filesystem::path& dir) {
    // Nothing is upsampled without GI or at trace scale 1 (every pixel traced): no weights to write.
    if (!renderer.voxelGrid() || renderer.settings().traceScale <= 1 || !renderer.settings().writeWeightSum)
        return {};
    FrameTargets& t = renderer.targets();
    std::vector<float> weights = renderer.readFloatImage(t.weightSum);
    std::vector<uint8_t> mask(size_t(t.width) * t.height * 4, 255);
    for (size_t i = 0; i * 4 < weights.size(); ++i) {
        const uint8_t v = weights[i * 4 + 2] > 0.5f ? 255 : 0;
        mask[i * 4] = mask[i * 4 + 1] = mask[i * 4 + 2] = v;
        weights[i * 4 + 3] = 1.0f;
    }
    writeExr(dir / "weight_sum.exr", t.width, t.height, weights);
    writePng(dir / "resample_mask.png", t.width, t.height, mask);
    return {"weight_sum.exr", "resample_mask.png"};
}

}  // namespace vct
