// The demo's path-traced reference (engine/reference/path_tracer.h) for side B of the split view: a worker
// thread that owns one PathTracer and adds one sample per pixel per pass, publishing the mean after each
// complete pass, while the frame loop goes on. The frame loop tells it every frame what it should be tracing
// (update): a new camera restarts the tracer (PathTracer::restart), a new scene, size, bounce count,
// environment or scene time at which something stands elsewhere (an animation moved a node) builds a new
// PathTracer, in both cases cancelling the pass under way through addSamples' cancel flag. While nothing
// changes (a paused animation, a scene without animation, a still camera) it keeps converging, up to
// kMaxSamplesPerPixel. Free of GLFW, ImGui and Vulkan: unit-tested (tests/demo_test.cpp).
//
// The scene is held by shared_ptr for as long as a tracer built from it lives (the tracer keeps a reference),
// so replacing the demo's scene can never leave the worker reading a freed one; the demo still stops the
// worker (destroys this object, which cancels and joins) when the scene changes, the split view is turned
// off or its source changes, and on exit.
//
// Lockstep (scripted runs, --frames/--script): every update asks for exactly one more pass than the last
// (one after a restart or rebuild) and waitForFrame() blocks until it is done, so frame k after a restart
// shows exactly k + 1 samples per pixel, the same image on every run: `vct reference --spp k+1` bit for bit.
// Interactively the frame loop never waits.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "app/cli/aux_output.h"
#include "reference/path_tracer.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace vct {

// What the reference should trace: the frame side A renders.
struct ReferenceRequest {
    std::shared_ptr<const Scene> scene;
    float timeSeconds = 0.0f;
    CameraView camera;
    uint32_t width = 0, height = 0;
    int bounces = 1;               // reference::ReferenceSettings::bounces (kUnlimitedBounces: all)
    glm::vec3 environment{0.03f};  // RenderSettings::ambient
    // The environment side A renders with (Renderer::sharedEnvironment); replaces `environment` when set.
    std::shared_ptr<const EnvironmentMap> environmentMap;
};

// The latest complete pass, as the frame loop reads it.
struct ReferenceSnapshot {
    std::shared_ptr<const reference::ReferenceImages> images;  // null until a pass completed
    uint64_t version = 0;          // increases with every published pass (to redo the tone map only then)
    uint32_t samplesPerPixel = 0;  // of `images`
    bool current = false;          // `images` is of the latest request (not of a camera/time before it)
    double raysPerSecond = 0.0;    // of the last pass
    uint32_t threads = 0;
    std::string state;  // "building", "tracing", "converged", or the error that stopped it
    bool failed = false;
};

class DemoReference {
  public:
    static constexpr uint32_t kMaxSamplesPerPixel = 1u << 16;

    // Starts the worker; `threads` path-tracing threads (0: every hardware thread).
    explicit DemoReference(uint32_t threads);
    // Cancels the pass under way and joins the worker (which drops its tracer, then its scene).
    ~DemoReference();
    DemoReference(const DemoReference&) = delete;
    DemoReference& operator=(const DemoReference&) = delete;

    // The frame loop, every frame: trace `request`. Returns true when that restarted or rebuilt the tracer.
    bool update(const ReferenceRequest& request, bool lockstep);
    // Lockstep: blocks until the pass the last update asked for is published (or the tracer failed).
    void waitForFrame();
    ReferenceSnapshot snapshot() const;
    uint32_t threads() const { return threads_; }

  private:
    void run();
    void publish(std::shared_ptr<const reference::ReferenceImages> images, uint64_t generation, uint32_t spp,
                 double raysPerSecond, const std::string& state, bool failed);

    const uint32_t threads_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;       // the worker: a new request, a higher target or quit
    std::condition_variable published_;  // waitForFrame: a pass or a state was published
    std::atomic<bool> cancel_{false};
    bool quit_ = false;
    ReferenceRequest request_;
    uint64_t generation_ = 0;  // of request_: increases when it needs a restart or rebuild
    uint32_t target_ = 0;      // samples per pixel wanted for request_
    // Published by the worker.
    ReferenceSnapshot snapshot_;
    uint64_t publishedGeneration_ = 0;  // the request generation snapshot_'s state is of
    uint64_t imagesGeneration_ = 0;     // ... and snapshot_.images
    uint32_t workerSpp_ = 0;            // the tracer's samples per pixel for publishedGeneration_
    std::thread worker_;
};

// Path-tracing threads for the demo: 1 on a CPU Vulkan device (lavapipe renders the frames on the same cores;
// one tracing thread keeps the window's frame rate), all but one on a GPU machine (one core left for the
// frame loop and the driver).
uint32_t demoReferenceThreads(bool cpuDevice);

// `images`' buffer for the demo's view (direct, diffuse, specular: the reference's own; any other: final)
// as RGBA8: exposed, ACES tone mapped, sRGB encoded, like `vct reference`'s final.png and the demo's views.
std::vector<uint8_t> referencePixels(const reference::ReferenceImages& images, AuxView view, float exposure);

}  // namespace vct
