// The demo's Dear ImGui windows: the control panel (a widget for every setting whose row in the setting table
// has one, render/setting_table.h; the views, the split view, scene,
// animation, camera path, shader reload) and the timer overlay (per-pass GPU medians as bars, frame-time
// graph, fps, re-traced fraction, device, sizes). Every change goes through applyOption, like --script.
#pragma once

#include <string>

#include "app/demo/demo_controls.h"
#include "app/demo/demo_timers.h"

namespace vct {

// What the panel shows besides the controls themselves.
struct PanelInfo {
    std::string device, scene;
    uint32_t width = 0, height = 0;
    uint32_t traceScale = 1, traceScaleB = 1;
    RenderSettings
        resolved;  // renderer A's settings: what it resolved automatic requests (voxels, anisotropy) to
    uint32_t voxelMips = 1;
    bool gi = true, giB = true;
    float resampled = 0.0f, resampledB = 0.0f;  // fraction of the pixels re-traced last frame
    double cpuFrameMs = 0.0;                    // wall-clock time of the last frame (render + present)
    const RollingTimers* timersA = nullptr;
    const RollingTimers* timersB = nullptr;        // split view only
    const RollingTimers* timersDisplay = nullptr;  // view, ui, blit
    const History* frameTimes = nullptr;
    float animationTime = 0.0f;
    // Side B as the path-traced reference (split-source reference).
    bool reference = false;
    uint32_t referenceSpp = 0;       // of the current camera and time (0 while the first pass runs)
    uint32_t referenceShownSpp = 0;  // of the image shown (an earlier view's while restarting)
    double referenceRaysPerSecond = 0.0;
    uint32_t referenceThreads = 0;
    std::string referenceState;
    bool hasCameraPath = false;
    bool recording = false;
    size_t recordedKeys = 0;
    std::string recordPath;
    std::string progress;  // a scene loading or shaders compiling: shown with a spinner-like dot count
    std::string message;   // the last thing that happened (screenshot written, shaders reloaded)
    std::string error;     // the last error (scene file, renderer, shader compiler output)
};

// Draws both windows for this ImGui frame. `sceneField` is the file field's buffer (kept by the caller).
void drawPanel(DemoControls& controls, PanelInfo& info, char* sceneField, size_t sceneFieldSize);

}  // namespace vct
