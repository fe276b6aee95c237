// vct demo: the same frame as `vct render`, live in a window, with a fly camera. Each frame is rendered by
// the Renderer exactly as headless, then blitted into a swapchain image inside the same submit.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "app/cli.h"
#include "app/commands.h"
#include "app/fly_camera.h"
#include "app/session.h"
#include "app/window.h"
#include "core/error.h"
#include "io/image_io.h"

namespace vct {

namespace {

CommandSpec makeDemoSpec() {
    std::vector<Option> options = {
        {"scene", "NAME|FILE", "built-in scene name (see vct scenes) or a .gltf/.glb file", "cornell"},
        {"size", "WxH", "initial window size", "1280x720"},
        {"frames", "N", "quit after N frames, advancing the scene 1/60 s per frame (0: run until closed)",
         "0"},
        {"screenshot", "FILE.png", "write the last frame to FILE.png on exit", ""},
        {"exposure", "X", "linear exposure before tone mapping", "1"},
        {"device", "SUBSTRING", "use the first Vulkan device whose name contains SUBSTRING", ""},
        {"validate", "", "enable the Khronos validation layer; any message fails the run", ""}};
    // The same GI and material-filtering switches as `render`, so the window can compare them live.
    for (Option& option : materialFilterOptions()) options.push_back(std::move(option));
    for (Option& option : giOptions()) options.push_back(std::move(option));
    for (Option& option : upsampleOptions()) options.push_back(std::move(option));
    return CommandSpec("demo", "Opens a window and shows the frame live (WASD + mouse drag, Esc quits).",
                       options);
}

const CommandSpec& demoSpec() {
    static const CommandSpec spec = makeDemoSpec();
    return spec;
}

constexpr float kLookRadiansPerPixel = 0.004f;
constexpr double kTitleInterval = 0.5;  // seconds between title updates: readable, and cheap

// Keys held and mouse drags since the last frame, as fly-camera input.
class InputReader {
  public:
    explicit InputReader(GLFWwindow* window) : window_(window) {
        // A key pressed and released between two polls (Esc at a few fps on a CPU device) still counts.
        glfwSetInputMode(window, GLFW_STICKY_KEYS, GLFW_TRUE);
    }

    FlyInput read(float dt) {
        FlyInput input;
        input.dt = dt;
        input.move.x = axis(GLFW_KEY_D, GLFW_KEY_A);
        input.move.y = axis(GLFW_KEY_E, GLFW_KEY_Q);
        input.move.z = axis(GLFW_KEY_W, GLFW_KEY_S);
        input.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
        double x = 0.0, y = 0.0;
        glfwGetCursorPos(window_, &x, &y);
        const bool dragging = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
                              glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        // Only motion while a button stays held turns the camera, so a click does not jump the view.
        if (dragging && wasDragging_)
            input.look = glm::vec2(float(x - lastX_), float(lastY_ - y)) * kLookRadiansPerPixel;
        wasDragging_ = dragging;
        lastX_ = x;
        lastY_ = y;
        return input;
    }

  private:
    bool down(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }
    float axis(int positive, int negative) const { return float(down(positive)) - float(down(negative)); }

    GLFWwindow* window_;
    bool wasDragging_ = false;
    double lastX_ = 0.0, lastY_ = 0.0;
};

// "vct demo | cornell | 60.0 fps | shadow 0.10  gbuffer 0.21 ... ms (GPU)"
std::string windowTitle(const std::string& scene, double fps, const Renderer& renderer) {
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%.1f fps", fps);
    std::string title = "vct demo | " + scene + " | " + buffer + " |";
    for (const auto& [name, ms] : renderer.timer().lastFrame()) {
        std::snprintf(buffer, sizeof(buffer), " %s %.2f", name.c_str(), ms);
        title += buffer;
    }
    return title + " ms (GPU)";
}

// The frame loop; returns the number of frames shown.
uint32_t runLoop(Window& window, Session& session, Swapchain& swapchain, uint32_t frameLimit) {
    Renderer& renderer = session.renderer();
    const Aabb bounds = renderer.gpuScene().scene().bounds();
    // Crossing the scene takes a few seconds whatever its units.
    const float sceneSize = bounds.empty() ? 1.0f : std::max(glm::length(bounds.max - bounds.min), 1e-3f);
    FlyCamera camera(sceneCamera(session.scene(), 0.0f), 0.3f * sceneSize);
    InputReader inputReader(window.handle());
    // Scripted runs (--frames) step a fixed 1/60 s so that their frames, and screenshots, are reproducible.
    const bool fixedStep = frameLimit > 0;
    const double start = glfwGetTime();
    double last = start, titleStart = start;
    uint32_t frame = 0, titleFrames = 0;

    while (!glfwWindowShouldClose(window.handle()) && (frameLimit == 0 || frame < frameLimit)) {
        glfwPollEvents();
        if (glfwGetKey(window.handle(), GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
        if (window.takeResized() || swapchain.stale()) {
            if (!swapchain.recreate()) {  // minimised: nothing to show until the window has a size again
                glfwWaitEvents();
                continue;
            }
            const VkExtent2D extent = swapchain.extent();
            if (extent.width != renderer.settings().width || extent.height != renderer.settings().height)
                renderer.resize(extent.width, extent.height);
        }

        const double now = glfwGetTime();
        // Clamped so that a stall (a resize, a dragged window) does not fling the camera away.
        const float dt = fixedStep ? 1.0f / 60.0f : float(std::min(now - last, 0.25));
        last = now;
        camera.update(inputReader.read(dt));

        SwapchainImage image;
        if (!swapchain.acquire(image)) continue;
        FrameInput input;
        input.camera = camera.view();
        input.timeSeconds = fixedStep ? float(frame) / 60.0f : float(now - start);
        input.cut = frame == 0;
        FrameSubmit submit;
        submit.afterPasses = [&](VkCommandBuffer cmd) {
            swapchain.recordBlit(cmd, renderer.targets().ldr, image);
        };
        submit.wait = image.available;
        submit.waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        submit.signal = image.rendered;
        renderer.render(input, submit);
        swapchain.present(image);
        ++frame;

        ++titleFrames;
        if (now - titleStart >= kTitleInterval) {
            const double fps = titleFrames / (now - titleStart);
            glfwSetWindowTitle(window.handle(), windowTitle(session.scene().name, fps, renderer).c_str());
            titleStart = now;
            titleFrames = 0;
        }
    }
    return frame;
}

}  // namespace

int runDemoCommand(int argc, char** argv, int first) {
    auto parsed = demoSpec().parse(argc, argv, first);
    if (!parsed) return 0;
    const ParsedArgs& args = *parsed;
    SessionOptions options = sessionOptions(args);
    const uint32_t frameLimit = args.getUint("frames", 0, 100000000);
    const std::string screenshot = args.get("screenshot");

    {
        // Declared in this order so they are destroyed in reverse: the swapchain and surface while the
        // Vulkan instance and device live, the instance before GLFW closes its display connection.
        Window window("vct demo", options.settings.width, options.settings.height);
        options.context.instanceExtensions = window.requiredInstanceExtensions();
        options.context.swapchain = true;
        // The renderer starts at the framebuffer's size (it differs from --size on high-DPI displays).
        const VkExtent2D framebuffer = window.framebufferSize();
        if (framebuffer.width > 0 && framebuffer.height > 0) {
            options.settings.width = framebuffer.width;
            options.settings.height = framebuffer.height;
        }
        Session session(options);
        Swapchain swapchain(session.context(), window);

        std::printf(
            "controls: W/A/S/D move, Q/E down/up, Shift faster, "
            "drag with a mouse button to look, Esc quits\n");
        std::fflush(stdout);
        const uint32_t frames = runLoop(window, session, swapchain, frameLimit);

        if (!screenshot.empty()) {
            if (frames == 0) throw Error("no frame was shown, so no screenshot was written");
            Renderer& renderer = session.renderer();
            writePng(screenshot, renderer.settings().width, renderer.settings().height, renderer.readLdr());
            std::printf("wrote %s\n", screenshot.c_str());
        }
    }
    // Counted after the device is destroyed, so leaks reported at teardown fail the run too.
    checkValidation(options);
    return 0;
}

}  // namespace vct
