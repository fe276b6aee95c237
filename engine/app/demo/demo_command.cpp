// vct demo: the frame of `vct render`, live in a window, with a fly camera, a Dear ImGui panel for every live
// setting, a per-pass GPU timer overlay, the split view, scene loading, camera paths, scripts and shader hot
// reload. One frame: input and script steps → applyOption → renderers brought to the settings → the frame
// rendered (side A, and side B for the split view; or the path-traced reference told what to trace, on its
// own thread: app/demo/demo_reference.h) → views and UI composed in the window (app/demo/demo_display.h).
#define GLFW_INCLUDE_VULKAN
#include "app/demo/demo_command.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <optional>
#include <string>

#include "app/cli/cli.h"
#include "app/cli/session.h"
#include "app/demo/demo_controls.h"
#include "app/demo/demo_display.h"
#include "app/demo/demo_input.h"
#include "app/demo/demo_panel.h"
#include "app/demo/demo_reference.h"
#include "app/demo/demo_renderers.h"
#include "app/demo/demo_script.h"
#include "app/demo/demo_timers.h"
#include "app/demo/fly_camera.h"
#include "app/demo/shader_reload.h"
#include "app/demo/window.h"
#include "core/error.h"
#include "io/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/camera_path.h"

namespace vct {

namespace {

// --size: the window's initial size.
Option windowSize() {
    Option size = settingOption("size");
    size.help += " (the window's initial size)";
    return size;
}

CommandSpec makeDemoSpec() {
    std::vector<Option> options = {
        {"scene", "NAME|FILE", "built-in scene name (see vct scenes) or a .gltf/.glb file", "cornell"},
        windowSize(),
        {"frames", "N", "quit after N frames, advancing the scene 1/60 s per frame (0: run until closed)",
         "0"},
        {"screenshot", "FILE.png", "write the last frame to FILE.png on exit", ""},
        {"script", "FILE.json",
         "replay a session: [{\"frame\": N, \"set\": {option: value}}, {\"frame\": N, \"screenshot\": "
         "\"a.png\"}]; "
         "quits after its last step (screenshots relative to, and confined to, the script's directory)",
         ""},
        {"script-outputs-anywhere", "", "let --script screenshots write outside the script's directory", ""},
        {"camera-path", "FILE.json", "play this keyframed camera path (toggle in the panel)", ""},
        {"record-path", "FILE.json", "where R (record camera path) writes the recorded path",
         "camera_path.json"},
        {"view", "BUFFER",
         "what the window shows: final, direct, diffuse, specular, normals, roughness, weights, resample, "
         "voxels",
         "final"},
        {"voxel-mip", "M", "--view voxels: the mip shown", "0"},
        {"panel", "on|off", "show the panel and timers at start (F1 toggles)", "on"},
        {"frames-in-flight", "1|2",
         "frames the CPU may record ahead of the GPU: 2 overlaps recording with the frame before, 1 waits "
         "for "
         "each frame",
         "2"},
        {"split", "on|off", "split view at start (V toggles): side A left of the wipe, B right", "off"},
        {"split-source", "vct|reference",
         "what side B shows: vct with its own settings (b-NAME in scripts) or the path-traced reference, "
         "converging on a CPU thread",
         "vct"},
        {"reference-bounces", "0..64|all",
         "the reference's indirect bounces: all is full GI (what vct's default converges to), 1 what vct "
         "estimates with --bounces 1",
         "all"},
        settingOption("exposure"),
        {"device", "SUBSTRING", "use the first Vulkan device whose name contains SUBSTRING", ""},
        {"validate", "", "enable the Khronos validation layer; any message fails the run", ""}};
    // The same GI and material-filtering switches as `render`; the panel changes them live.
    for (SettingGroup group : {SettingGroup::Material, SettingGroup::Gi, SettingGroup::Upsample})
        for (Option& option : settingOptions(group)) options.push_back(std::move(option));
    return CommandSpec("demo",
                       "Opens a window and shows the frame live: WASD + mouse drag, F1 panel, Esc quits "
                       "(README: every control and key).",
                       options);
}

const CommandSpec& demoSpec() {
    static const CommandSpec spec = makeDemoSpec();
    return spec;
}

std::string secondsText(double seconds) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.1f s", seconds);
    return buffer;
}

// Work that runs off the frame loop (a scene parse, a shader compile) so the window keeps drawing.
template <typename T>
struct Job {
    std::future<T> future;
    std::string what;
    std::chrono::steady_clock::time_point start;

    bool running() const { return future.valid(); }
    // The result when done; when `wait` (scripted runs: reproducible frames) blocks until it is.
    std::optional<T> poll(bool wait) {
        if (!future.valid()) return std::nullopt;
        if (!wait && future.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
            return std::nullopt;
        return future.get();  // rethrows the job's exception
    }
    std::string progress() const {
        return what + " ... " +
               secondsText(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
};

struct DemoArgs {
    SessionOptions session;
    uint32_t frameLimit = 0;
    std::string screenshot;
    std::optional<DemoScript> script;
    std::optional<CameraPath> cameraPath;
    std::string recordPath;
    uint32_t framesInFlight = 2;
    DemoControls controls;
};

class DemoApp {
  public:
    DemoApp(Window& window, Swapchain& swapchain, vk::Context& context, DemoArgs& args,
            std::unique_ptr<Scene> scene)
        : window_(window),
          swapchain_(swapchain),
          context_(context),
          args_(args),
          controls_(args.controls),
          renderers_(context, std::move(scene), withViewNeeds(args.controls.settings, args.controls.view),
                     args.framesInFlight),
          display_(context, window, args.framesInFlight),
          input_(window.handle()) {
        fixedStep_ = args.frameLimit > 0 || args.script.has_value();
        resetCamera();
        info_.device = context.deviceName();
        info_.hasCameraPath = args.cameraPath.has_value();
        info_.recordPath = args.recordPath;
        controls_.playPath = info_.hasCameraPath;
        printAnisotropy(args.controls.settings.anisotropy, renderers_.a().settings().anisotropy);
    }

    ~DemoApp() {
        // A hot reload's SPIR-V directory (in the temp directory) is this process's own.
        const std::filesystem::path dir = currentShaderDir();
        if (dir.filename().string().rfind("vct-shaders-", 0) == 0) {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    }

    // The frame loop; returns the number of frames shown.
    uint32_t run();
    Renderer& renderer() { return renderers_.a(); }
    // Waits for the frames still in flight and takes their timings.
    void finishFrames();
    void printTimers() const;

  private:
    void resetCamera();
    void handleKeys();
    void applyScript();
    void runJobs();
    void updateCamera(float dt, FrameInput& input);
    void recordKey(const CameraView& camera);
    void present();
    void fillInfo(double cpuMs);
    DisplaySource source(Renderer& renderer, std::vector<uint8_t>& pixels);
    void updateReference(const FrameInput& input);
    DisplaySource referenceSource();
    float animationTime() const {
        return fixedStep_ ? float(animationTicks_) / 60.0f : float(animationSeconds_);
    }

    Window& window_;
    Swapchain& swapchain_;
    vk::Context& context_;
    DemoArgs& args_;
    DemoControls& controls_;
    DemoRenderers renderers_;
    DemoDisplay display_;
    DemoInput input_;
    std::optional<FlyCamera> camera_;
    bool fixedStep_ = false;
    uint32_t frame_ = 0;
    uint64_t animationTicks_ = 0;  // fixed-step clock: 1/60 s each (exact, like vct render)
    double animationSeconds_ = 0.0;
    bool cut_ = true;  // the next frame has no history
    RollingTimers timersA_, timersB_, timersDisplay_;
    History frameTimes_;
    PanelInfo info_;
    char sceneField_[512] = "";
    Job<Scene> sceneJob_;
    std::unique_ptr<Scene>
        loadedScene_;  // parsed, uploaded on the next frame (after the progress line shows)
    Job<ShaderBuild> shaderJob_;
    int reloads_ = 0;
    bool recording_ = false;
    CameraPath recorded_;
    double recordStart_ = 0.0;
    std::vector<uint8_t> pixelsA_, pixelsB_;
    // Side B as the path-traced reference (split-source reference): its worker runs while this exists.
    // Declared after renderers_, so it is stopped first (it holds its own share of the scene anyway).
    std::unique_ptr<DemoReference> reference_;
    ReferenceSnapshot referenceShown_;  // what pixelsReference_ shows (made from its version)
    uint64_t referenceVersion_ = 0;
    float referenceExposure_ = 0.0f;
    std::string referenceError_;  // the last failure reported
    AuxView referenceView_ = AuxView::Final;
    std::vector<uint8_t> pixelsReference_;
};

void DemoApp::resetCamera() {
    const Scene& scene = renderers_.scene();
    const Aabb bounds = scene.bounds();
    // Crossing the scene takes a few seconds whatever its units.
    const float size = bounds.empty() ? 1.0f : std::max(glm::length(bounds.max - bounds.min), 1e-3f);
    camera_.emplace(sceneCamera(scene, 0.0f), 0.3f * size);
    info_.scene = scene.name;
    cut_ = true;
}

void DemoApp::handleKeys() {
    // Edges are read every frame (so a press is not replayed later); acted on when the panel has no text
    // focus.
    const bool keys = !ImGui::GetIO().WantCaptureKeyboard;
    auto key = [&](int k) { return input_.pressed(k) && keys; };
    if (key(GLFW_KEY_F1)) controls_.panel = !controls_.panel;
    if (key(GLFW_KEY_F5)) controls_.hotReload = true;
    if (key(GLFW_KEY_F12))
        applyOption(controls_, "screenshot", "vct-demo-" + std::to_string(frame_) + ".png");
    if (key(GLFW_KEY_P)) controls_.paused = !controls_.paused;
    if (key(GLFW_KEY_N)) controls_.step = true;
    if (key(GLFW_KEY_H)) controls_.resetHistory = true;
    if (key(GLFW_KEY_C)) controls_.cameraCut = true;
    if (key(GLFW_KEY_R)) controls_.toggleRecording = true;
    if (key(GLFW_KEY_V)) controls_.split = !controls_.split;
    const std::string dropped = window_.takeDroppedFile();
    if (!dropped.empty()) controls_.openScene = dropped;
}

void DemoApp::applyScript() {
    if (!args_.script) return;
    for (const ScriptStep& step : args_.script->steps) {
        if (step.frame != frame_) continue;
        for (const auto& [name, value] : step.options) {
            applyOption(controls_, name, value);
            std::printf("frame %u: %s %s\n", frame_, name.c_str(), value.c_str());
        }
    }
}

void DemoApp::runJobs() {
    // A scene parsed last frame: upload it now (the progress line said so for a frame).
    if (loadedScene_) {
        try {
            renderers_.replaceScene(std::move(loadedScene_), controls_);
            reference_.reset();  // joins the worker; the next frame starts one on the new scene
            resetCamera();
            info_.message = "loaded " + renderers_.scene().name + " (" + renderers_.lastRebuild() + ")";
            std::printf("%s\n", info_.message.c_str());
        } catch (const Error& e) {
            info_.error = std::string("cannot show the scene: ") + e.what();
        }
        loadedScene_.reset();
        info_.progress.clear();
    }
    if (!controls_.openScene.empty() && !sceneJob_.running()) {
        const std::string path = std::exchange(controls_.openScene, std::string());
        sceneJob_ = {std::async(std::launch::async, [path] { return loadScene(path); }), "loading " + path,
                     std::chrono::steady_clock::now()};
    }
    try {
        if (std::optional<Scene> scene = sceneJob_.poll(fixedStep_)) {
            for (const std::string& note : scene->notes) std::printf("note: %s\n", note.c_str());
            loadedScene_ = std::make_unique<Scene>(std::move(*scene));
            info_.progress = "uploading and voxelizing " + loadedScene_->name;
            if (fixedStep_) runJobs();  // scripted: no frame in between
            return;
        }
    } catch (const Error& e) {
        // The previous scene keeps running.
        info_.error = e.what();
        std::fprintf(stderr, "scene: %s\n", e.what());
    }
    if (controls_.hotReload && !shaderJob_.running()) {
        controls_.hotReload = false;
        const std::filesystem::path out =
            std::filesystem::temp_directory_path() /
            ("vct-shaders-" + std::to_string(getpid()) + "-" + std::to_string(++reloads_));
        const std::filesystem::path source = shaderSourceDir();
        shaderJob_ = {std::async(std::launch::async, [source, out] { return compileShaders(source, out); }),
                      "compiling shaders", std::chrono::steady_clock::now()};
    }
    if (std::optional<ShaderBuild> build = shaderJob_.poll(fixedStep_)) {
        if (!build->ok) {
            // The old pipelines keep running.
            info_.error = "shader compile failed, old pipelines kept:\n" + build->log;
            std::fprintf(stderr, "hot reload: %s\n", info_.error.c_str());
            std::error_code ignored;
            std::filesystem::remove_all(build->dir, ignored);
        } else {
            const std::filesystem::path previous = currentShaderDir();
            useShaderDir(build->dir);
            try {
                renderers_.rebuild(controls_);
                info_.message = "shaders reloaded: " + build->log;
                info_.error.clear();
                cut_ = true;
                std::printf("hot reload: %s from %s\n", build->log.c_str(), build->dir.c_str());
                // The directory before (a previous reload's) is no longer read.
                if (previous.filename().string().rfind("vct-shaders-", 0) == 0)
                    std::filesystem::remove_all(previous);
            } catch (const Error& e) {
                useShaderDir(previous);
                info_.error = std::string("new pipelines failed, old ones kept: ") + e.what();
                std::filesystem::remove_all(build->dir);
            }
        }
    }
    info_.progress = sceneJob_.running()    ? sceneJob_.progress()
                     : shaderJob_.running() ? shaderJob_.progress()
                                            : info_.progress;
}

void DemoApp::updateCamera(float dt, FrameInput& input) {
    const ImGuiIO& io = ImGui::GetIO();
    const bool mouse = !io.WantCaptureMouse;
    const float wipe = input_.dragWipe(controls_.wipe, controls_.split, mouse);
    if (wipe >= 0.0f) controls_.wipe = wipe;
    const FlyInput fly = input_.fly(dt, !io.WantCaptureKeyboard, mouse);
    const bool flying = fly.look != glm::vec2(0.0f) || fly.move != glm::vec3(0.0f);
    const float t = animationTime();
    const CameraView sceneView = sceneCamera(renderers_.scene(), t);
    if (controls_.playPath && args_.cameraPath) {
        if (flying) {
            // Taking the controls leaves the path where it is.
            controls_.playPath = false;
            camera_.emplace(args_.cameraPath->evaluate(t, sceneView), camera_->speed());
        }
    }
    if (controls_.cameraCut) {
        const CameraView from = controls_.playPath && args_.cameraPath
                                    ? args_.cameraPath->evaluate(t, sceneView)
                                    : camera_->view();
        controls_.playPath = false;
        camera_.emplace(cutCamera(from), camera_->speed());
        cut_ = true;
        controls_.cameraCut = false;
    }
    if (controls_.playPath && args_.cameraPath) {
        input.camera = args_.cameraPath->evaluate(t, sceneView);
    } else {
        camera_->update(fly);
        input.camera = camera_->view();
    }
    if (controls_.resetHistory) cut_ = true;
    controls_.resetHistory = false;
}

void DemoApp::recordKey(const CameraView& camera) {
    const double now = fixedStep_ ? double(frame_) / 60.0 : glfwGetTime();
    if (controls_.toggleRecording) {
        controls_.toggleRecording = false;
        if (!recording_) {
            recording_ = true;
            recorded_ = CameraPath{};
            recorded_.scene = renderers_.scene().name;
            recorded_.yfov = camera.yfov;
            recorded_.znear = camera.znear;
            recorded_.zfar = camera.zfar;
            recordStart_ = now;
            info_.message = "recording the camera path (R stops)";
        } else {
            recording_ = false;
            try {
                if (recorded_.keys.size() < 2)
                    throw Error("a path needs at least two keys: record for longer");
                saveCameraPath(recorded_, args_.recordPath);
                info_.message =
                    "wrote " + args_.recordPath + " (" + std::to_string(recorded_.keys.size()) + " keys)";
                std::printf("%s\n", info_.message.c_str());
            } catch (const Error& e) {
                info_.error = e.what();
            }
        }
    }
    if (!recording_) return;
    // A key every 0.25 s: Catmull-Rom through them replays the flight smoothly.
    const float t = float(now - recordStart_);
    if (recorded_.keys.empty() || t - recorded_.keys.back().time >= 0.25f)
        recorded_.keys.push_back(cameraKey(camera, t));
    info_.recording = recording_;
    info_.recordedKeys = recorded_.keys.size();
}

// The side's picture for the display: the LDR frame itself, or a view made from its buffers on the CPU.
DisplaySource DemoApp::source(Renderer& renderer, std::vector<uint8_t>& pixels) {
    const RenderSettings& s = renderer.settings();
    const AuxView view = controls_.view;
    const bool available = !(auxViewNeedsGi(view) && !s.gi) &&
                           !((view == AuxView::Resample || view == AuxView::Weights) && s.traceScale <= 1);
    if (view == AuxView::Final || !available) return {&renderer.targets().ldr, nullptr};
    const uint32_t mip =
        renderer.voxelGrid() ? std::min(controls_.voxelMip, renderer.voxelGrid()->mipCount() - 1) : 0;
    pixels = viewImage(renderer, view, mip);
    return {nullptr, &pixels};
}

void DemoApp::updateReference(const FrameInput& input) {
    if (!controls_.showsReference()) {
        reference_.reset();  // cancels the pass under way and joins the worker
        return;
    }
    if (!reference_)
        reference_ = std::make_unique<DemoReference>(
            demoReferenceThreads(context_.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU));
    ReferenceRequest request;
    request.scene = renderers_.sharedScene();
    request.timeSeconds = input.timeSeconds;
    request.camera = input.camera;
    request.width = controls_.settings.width;
    request.height = controls_.settings.height;
    request.bounces = controls_.referenceBounces;
    request.environment = controls_.settings.ambient;
    request.environmentMap = renderers_.a().sharedEnvironment();
    // Scripted runs go in lockstep (one pass per frame, waited for) so that they are reproducible.
    reference_->update(request, fixedStep_);
}

// Side B as the reference's latest complete pass, tone mapped again only when it, the exposure or the view
// changed; black until a pass of the window's size is done.
DisplaySource DemoApp::referenceSource() {
    const ReferenceSnapshot latest = reference_->snapshot();
    const uint32_t w = controls_.settings.width, h = controls_.settings.height;
    const float exposure = controls_.settings.exposure;
    const bool fits = latest.images && latest.images->width == w && latest.images->height == h;
    if (!fits) {
        pixelsReference_.assign(size_t(w) * h * 4, 0);
        for (size_t i = 3; i < pixelsReference_.size(); i += 4) pixelsReference_[i] = 255;
        referenceShown_ = {};
        referenceVersion_ = 0;
        return {nullptr, &pixelsReference_};
    }
    if (latest.version != referenceVersion_ || exposure != referenceExposure_ ||
        controls_.view != referenceView_) {
        pixelsReference_ = referencePixels(*latest.images, controls_.view, exposure);
        referenceVersion_ = latest.version;
        referenceExposure_ = exposure;
        referenceView_ = controls_.view;
    }
    referenceShown_ = latest;
    return {nullptr, &pixelsReference_};
}

void DemoApp::fillInfo(double cpuMs) {
    Renderer& a = renderers_.a();
    info_.width = a.settings().width;
    info_.height = a.settings().height;
    info_.traceScale = a.settings().gi ? a.settings().traceScale : 1;
    info_.gi = a.settings().gi;
    info_.resolved = a.settings();
    info_.voxelMips = a.voxelGrid() ? a.voxelGrid()->mipCount() : 1;
    info_.resampled = a.resampledFraction();
    info_.cpuFrameMs = cpuMs;
    info_.timersA = &timersA_;
    info_.timersB = renderers_.b() ? &timersB_ : nullptr;
    info_.timersDisplay = &timersDisplay_;
    info_.frameTimes = &frameTimes_;
    info_.animationTime = animationTime();
    info_.reference = reference_ != nullptr;
    if (reference_) {
        const ReferenceSnapshot snapshot = reference_->snapshot();
        info_.referenceSpp = snapshot.current ? snapshot.samplesPerPixel : 0;
        info_.referenceShownSpp = snapshot.samplesPerPixel;
        info_.referenceRaysPerSecond = snapshot.raysPerSecond;
        info_.referenceThreads = snapshot.threads;
        info_.referenceState = snapshot.state;
        if (snapshot.failed && snapshot.state != referenceError_) {
            referenceError_ = snapshot.state;
            info_.error = "reference: " + snapshot.state;
            std::fprintf(stderr, "%s\n", info_.error.c_str());
        }
    }
}

uint32_t DemoApp::run() {
    const uint32_t limit = args_.frameLimit > 0 ? args_.frameLimit
                           : args_.script       ? args_.script->lastFrame() + 1
                                                : 0;
    double last = glfwGetTime(), titleStart = last;
    uint32_t titleFrames = 0;
    while (!glfwWindowShouldClose(window_.handle()) && (limit == 0 || frame_ < limit) && !controls_.quit) {
        glfwPollEvents();
        if (glfwGetKey(window_.handle(), GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
        if (window_.takeResized() || swapchain_.stale()) {
            if (!swapchain_.recreate()) {  // minimised: nothing to show until the window has a size again
                glfwWaitEvents();
                continue;
            }
        }
        controls_.settings.width = swapchain_.extent().width;
        controls_.settings.height = swapchain_.extent().height;

        handleKeys();
        applyScript();
        runJobs();
        try {
            renderers_.sync(controls_);
        } catch (const Error& e) {
            info_.error = e.what();
            std::fprintf(stderr, "%s\n", e.what());
        }

        const double now = glfwGetTime();
        // Clamped so that a stall (a resize, a new renderer) does not fling the camera away.
        const float dt = fixedStep_ ? 1.0f / 60.0f : float(std::min(now - last, 0.25));
        last = now;
        FrameInput input;
        updateCamera(dt, input);
        input.timeSeconds = animationTime();
        input.cut = std::exchange(cut_, false);
        updateReference(input);  // before rendering: the worker traces while the device renders side A
        renderers_.render(input);
        if (reference_ && fixedStep_) reference_->waitForFrame();  // scripted: one pass per frame
        timersA_.add(renderers_.a().timer().lastFrame());
        if (renderers_.b())
            timersB_.add(renderers_.b()->timer().lastFrame());
        else
            timersB_.clear();
        if (!controls_.paused || controls_.step) {
            ++animationTicks_;
            animationSeconds_ += dt;
        }
        controls_.step = false;
        recordKey(input.camera);

        present();
        ++frame_;
        const double after = glfwGetTime();
        frameTimes_.push(float((after - now) * 1000.0));
        fillInfo((after - now) * 1000.0);
        ++titleFrames;
        if (after - titleStart >= 0.5) {
            char title[128];
            std::snprintf(title, sizeof(title), "vct demo | %s | %.1f fps", renderers_.scene().name.c_str(),
                          titleFrames / (after - titleStart));
            glfwSetWindowTitle(window_.handle(), title);
            titleStart = after;
            titleFrames = 0;
        }
    }
    if (recording_) {  // a recording still running at exit is kept
        controls_.toggleRecording = true;
        recordKey(camera_->view());
    }
    return frame_;
}

void DemoApp::present() {
    SwapchainImage image;
    const DisplaySource a = source(renderers_.a(), pixelsA_);
    const DisplaySource b = reference_       ? referenceSource()
                            : renderers_.b() ? source(*renderers_.b(), pixelsB_)
                                             : DisplaySource{};
    const bool split = renderers_.b() != nullptr || reference_ != nullptr;
    // A screenshot without the UI leaves the panel out of this one frame.
    const bool ui = controls_.panel && (controls_.screenshot.empty() || controls_.screenshotUi);
    display_.beginUi();
    if (ui) drawPanel(controls_, info_, sceneField_, sizeof(sceneField_));
    if (!swapchain_.acquire(image)) {
        ImGui::EndFrame();
        return;
    }
    display_.present(swapchain_, image, a, b, split, controls_.wipe, ui);
    swapchain_.present(image);
    timersDisplay_.add(display_.timer().lastFrame());
    if (!controls_.screenshot.empty()) {
        const std::string file = std::exchange(controls_.screenshot, std::string());
        try {
            writePng(file, display_.width(), display_.height(), display_.read());
            info_.message = "wrote " + file;
            std::printf("frame %u: wrote %s\n", frame_, file.c_str());
            if (reference_) {
                // What B showed: the spp of that image, and whether it is of this frame's camera and time.
                std::printf("frame %u: reference %u spp%s, %.3f Mrays/s on %u threads\n", frame_,
                            referenceShown_.samplesPerPixel,
                            referenceShown_.current ? "" : " (previous view)",
                            referenceShown_.raysPerSecond * 1e-6, reference_->threads());
            }
        } catch (const Error& e) {
            info_.error = e.what();
        }
    }
}

void DemoApp::finishFrames() {
    renderers_.finishFrames();
    display_.finishFrames();
    if (args_.framesInFlight == 1) return;  // every frame's timings were taken in the loop
    // The last frame's, taken now (the loop took each earlier frame's one frame late).
    timersA_.add(renderers_.a().timer().lastFrame());
    if (renderers_.b()) timersB_.add(renderers_.b()->timer().lastFrame());
    timersDisplay_.add(display_.timer().lastFrame());
}

void DemoApp::printTimers() const {
    auto line = [](const char* what, const RollingTimers& timers) {
        if (timers.frames() == 0) return;
        std::printf("%s (GPU median of the last %zu frames): total %.3f ms |", what, timers.frames(),
                    timers.frameMedianMs());
        for (const auto& bar : timers.medians()) std::printf(" %s %.3f", bar.name.c_str(), bar.medianMs);
        std::printf("\n");
    };
    line("renderer A", timersA_);
    line("renderer B (split view)", timersB_);
    line("window (view, ui, blit)", timersDisplay_);
    // The loop's own time per frame (input, panel, recording and submitting, waiting for the frame in flight):
    // what the window's frame rate is, GPU and CPU overlapped or not.
    const std::vector<float>& loop = frameTimes_.values();
    if (!loop.empty())
        std::printf(
            "frame loop (wall clock, median of the last %zu frames): %.3f ms, %u frame(s) in flight\n",
            loop.size(), median(std::vector<double>(loop.begin(), loop.end())), args_.framesInFlight);
    if (reference_) {
        const ReferenceSnapshot snapshot = reference_->snapshot();
        std::printf("reference (split view B): %u spp, %.3f Mrays/s on %u threads, %s\n",
                    snapshot.samplesPerPixel, snapshot.raysPerSecond * 1e-6, snapshot.threads,
                    snapshot.state.c_str());
    }
}

}  // namespace

int runDemoCommand(int argc, char** argv, int first) {
    auto parsed = demoSpec().parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& parsedArgs = *parsed;
    DemoArgs args;
    args.session = sessionOptions(parsedArgs);
    args.frameLimit = parsedArgs.getUint("frames", 0, 100000000);
    args.framesInFlight = parsedArgs.getUint("frames-in-flight", 1, 2);
    args.screenshot = parsedArgs.get("screenshot");
    args.recordPath = parsedArgs.get("record-path");
    if (parsedArgs.has("script"))
        args.script = loadDemoScript(parsedArgs.get("script"), parsedArgs.has("script-outputs-anywhere"));
    else if (parsedArgs.has("script-outputs-anywhere"))
        throw UsageError("--script-outputs-anywhere: only with --script");
    if (parsedArgs.has("camera-path")) args.cameraPath = loadCameraPath(parsedArgs.get("camera-path"));
    args.controls.settings = args.session.settings;
    applyOption(args.controls, "view", parsedArgs.get("view"));
    applyOption(args.controls, "voxel-mip", parsedArgs.get("voxel-mip"));
    applyOption(args.controls, "panel", parsedArgs.get("panel"));
    for (const char* name : {"split", "split-source", "reference-bounces"})
        applyOption(args.controls, name, parsedArgs.get(name));
    // The scene first: a bad file is reported before any window opens.
    auto scene = std::make_unique<Scene>(loadScene(args.session.scene));
    for (const std::string& note : scene->notes) std::printf("note: %s\n", note.c_str());

    uint32_t frames = 0;
    {
        // Declared in this order so they are destroyed in reverse: the swapchain and surface while the
        // Vulkan instance and device live, the instance before GLFW closes its display connection.
        Window window("vct demo", args.session.settings.width, args.session.settings.height);
        args.session.context.instanceExtensions = window.requiredInstanceExtensions();
        args.session.context.swapchain = true;
        // The renderer starts at the framebuffer's size (it differs from --size on high-DPI displays).
        const VkExtent2D framebuffer = window.framebufferSize();
        if (framebuffer.width > 0 && framebuffer.height > 0) {
            args.controls.settings.width = framebuffer.width;
            args.controls.settings.height = framebuffer.height;
        }
        vk::Context context(args.session.context);
        std::printf("device: %s\n", context.deviceName().c_str());
        {
            Swapchain swapchain(context, window);
            DemoApp app(window, swapchain, context, args, std::move(scene));
            std::printf(
                "controls: W/A/S/D move, Q/E down/up, Shift faster, drag to look, F1 panel, P pause, N step, "
                "H reset history, C camera cut, V split view, R record path, F5 reload shaders, F12 "
                "screenshot, "
                "Esc quits\n");
            std::fflush(stdout);
            frames = app.run();
            app.finishFrames();
            app.printTimers();
            if (!args.screenshot.empty()) {
                if (frames == 0) throw Error("no frame was shown, so no screenshot was written");
                Renderer& renderer = app.renderer();
                writePng(args.screenshot, renderer.settings().width, renderer.settings().height,
                         renderer.readLdr());
                std::printf("wrote %s\n", args.screenshot.c_str());
            }
        }
    }
    // Counted after the device is destroyed, so leaks reported at teardown fail the run too.
    checkValidation(args.session);
    return 0;
}

}  // namespace vct
