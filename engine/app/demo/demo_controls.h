// Everything the demo's panel, keys and --script can change, as plain data, and the one function that changes
// it by option name (applyOption): the panel, the keys and scripts all go through it, so a scripted run
// replays exactly what a user did. Names are the command-line flags (`--weights sg` ↔ applyOption("weights",
// "sg")); a few are demo actions (camera-cut, screenshot, ...). Free of GLFW, ImGui and Vulkan: unit-tested.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "app/cli/aux_output.h"
#include "reference/path_tracer.h"
#include "render/settings.h"

namespace vct {

// What side B of the split view shows: a second vct renderer (`settingsB()`) or the path-traced reference
// (app/demo/demo_reference.h) of the frame side A renders.
enum class SplitSource { Vct, Reference };

struct DemoControls {
    RenderSettings settings;  // the main configuration (side A of the split view); width/height: the window's
    // The split view (a wipe): side B renders the same frames with `settings` changed by these options
    // (applySetting names), e.g. {"weights": "normal"} as in Tokuyoshi 2015 Fig. 7. Both sides are really
    // rendered.
    bool split = false;
    std::map<std::string, std::string> splitOverrides = {{"weights", "normal"}};
    float wipe = 0.5f;  // where side B starts, as a fraction of the width
    SplitSource splitSource = SplitSource::Vct;
    // The reference's indirect bounces: -1 (all: full GI, what vct's default converges to), 1 (what vct estimates
    // with --bounces 1) or N.
    int referenceBounces = reference::kUnlimitedBounces;
    AuxView view = AuxView::Final;
    uint32_t voxelMip = 0;
    bool panel = true;      // F1
    bool paused = false;    // animation clock stopped (the camera still moves)
    bool playPath = false;  // the camera follows --camera-path

    // One-shot actions, consumed by the frame loop.
    bool step = false;          // advance a paused animation by one 1/60 s frame
    bool cameraCut = false;     // jump to another view, without history (like `render --camera-cut`)
    bool resetHistory = false;  // drop the temporal history (next frame is a cut, camera unchanged)
    bool hotReload = false;     // recompile the shaders and recreate the pipelines
    bool toggleRecording = false;
    bool quit = false;
    std::string screenshot;     // write this frame (as shown) to this PNG
    bool screenshotUi = false;  // ... with the panel and timers drawn over it
    std::string openScene;      // load this scene (built-in name or .gltf/.glb) in the background

    // Side B's settings: `settings` with splitOverrides applied.
    RenderSettings settingsB() const;
    // The split view is on and B is a vct renderer / the path-traced reference.
    bool rendersB() const { return split && splitSource == SplitSource::Vct; }
    bool showsReference() const { return split && splitSource == SplitSource::Reference; }
};

// Sets one RenderSettings field by its command-line name from its command-line text, with the command line's
// checks: the rows of the setting table (render/setting_table.h) marked `demo` (gi, trace-scale, voxels,
// weights, beta, kappa, sigma-n, diffuse-sharpness, gamma, tau, temporal, adaptive, toksvig, specular-aa,
// anisotropy, exposure). False when `name` is not such a setting; UsageError for a bad value (one line,
// naming the option).
bool applySetting(RenderSettings& settings, const std::string& name, const std::string& value);

// Applies a render setting (above), a demo option (view, voxel-mip, split, wipe, split-source vct|reference,
// reference-bounces 0..64|all, panel, pause, play-path, b-NAME: NAME for side B only) or an action
// (camera-cut, reset-history, step, hot-reload, record, quit, screenshot FILE, screenshot-ui FILE, scene
// FILE). UsageError for an unknown name or a bad value.
void applyOption(DemoControls& controls, const std::string& name, const std::string& value);

// The names applyOption takes, for the README and the error message.
const std::vector<std::string>& demoOptionNames();

// The values of split-source and reference-bounces as applyOption takes them ("reference", "all").
const char* splitSourceName(SplitSource source);
std::string referenceBouncesText(int bounces);

// A setting's current value as applyOption takes it ("sg", "4", "on", "0.25"); empty for unknown names.
std::string settingText(const RenderSettings& settings, const std::string& name);

}  // namespace vct
