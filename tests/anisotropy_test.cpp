// --anisotropy: the flag's values, the default chosen from the device, and what timings.json records. The
// renders are tiny (the built-in plane, GI off) because lavapipe emulates anisotropic filtering on the CPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_util.h"

namespace vct {
namespace {

namespace fs = std::filesystem;

// Renders one small frame of `plane` with validation on and `extra` flags; returns timings.json.
nlohmann::json renderPlane(const std::string& name, const std::vector<std::string>& extra, std::string* out) {
    const fs::path dir = test::freshOutputDir("anisotropy/" + name);
    std::vector<std::string> args = {"render", "--scene", "plane", "--size",     "96x54", "--frames",
                                     "1",      "--gi",    "off",   "--validate", "--out", dir.string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::RunResult run = test::runVct(args);
    EXPECT_TRUE(run.exited() && run.exitCode == 0) << run.describe();
    EXPECT_EQ(run.err.find("validation"), std::string::npos) << run.err;
    if (out) *out = run.out;
    std::ifstream file(dir / "timings.json");
    EXPECT_TRUE(file) << "no timings.json in " << dir;
    return file ? nlohmann::json::parse(file) : nlohmann::json::object();
}

TEST(Anisotropy, BadValuesAreOneLineUsageErrors) {
    for (const char* command : {"render", "demo", "benchmark"}) {
        for (const char* value : {"3", "1", "32", "-2", "eight", ""}) {
            const test::RunResult run = test::runVct({command, "--anisotropy", value});
            ASSERT_TRUE(run.exited()) << run.describe();
            EXPECT_EQ(run.exitCode, 2) << command << " --anisotropy '" << value << "'\n" << run.describe();
            EXPECT_NE(run.err.find("--anisotropy"), std::string::npos) << run.err;
            // One line: the message and its newline.
            EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        }
    }
}

TEST(Anisotropy, DefaultComesFromTheDeviceAndIsRecorded) {
    std::string out;
    const nlohmann::json timings = renderPlane("default", {}, &out);
    ASSERT_TRUE(timings.contains("anisotropy") && timings["anisotropy"].is_number_unsigned())
        << timings.dump(2);
    const uint32_t level = timings["anisotropy"].get<uint32_t>();
    EXPECT_NE(out.find("anisotropy: " + std::to_string(level) + " (default for this device)"),
              std::string::npos)
        << out;
    // lavapipe (the CI device) is a CPU device: off there. A GPU gets 8 (or its limit, a power of two).
    const std::string device = timings.value("device", "");
    if (device.find("llvmpipe") != std::string::npos)
        EXPECT_EQ(level, 0u) << device;
    else
        EXPECT_TRUE(level == 0 || level == 2 || level == 4 || level == 8) << level;
}

TEST(Anisotropy, OffAndSixteenBothRenderUnderValidation) {
    for (uint32_t level : {0u, 16u}) {
        std::string out;
        const nlohmann::json timings =
            renderPlane("level" + std::to_string(level), {"--anisotropy", std::to_string(level)}, &out);
        ASSERT_TRUE(timings.contains("anisotropy")) << timings.dump(2);
        const uint32_t used = timings["anisotropy"].get<uint32_t>();
        // 16 may be clamped on a device with a lower limit; then the startup line says so.
        if (used != level)
            EXPECT_NE(out.find("(the device's limit)"), std::string::npos) << out;
        else
            EXPECT_NE(out.find("anisotropy: " + std::to_string(level) + "\n"), std::string::npos) << out;
        EXPECT_LE(used, level);
    }
}

}  // namespace
}  // namespace vct
