#include "app/demo/demo_reference.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "render/shader_math.h"

namespace vct {

namespace {

bool sameCamera(const CameraView& a, const CameraView& b) {
    return a.view == b.view && a.yfov == b.yfov && a.znear == b.znear && a.zfar == b.zfar;
}

// What a PathTracer is built for, besides the camera (restart() changes only that).
bool sameBuild(const ReferenceRequest& a, const ReferenceRequest& b) {
    return a.scene == b.scene && a.timeSeconds == b.timeSeconds && a.width == b.width &&
           a.height == b.height && a.bounces == b.bounces && a.environment == b.environment &&
           a.environmentMap == b.environmentMap;
}

// Whether the scene stands exactly as it did: every node's pose (instances, lights) the same at both times.
// The clock runs in every frame that is not paused, but only an animation moving something needs a new
// tracer.
bool samePose(const Scene& scene, float a, float b) {
    if (a == b || scene.animations.empty()) return true;
    std::vector<glm::quat> rotationsA, rotationsB;
    return scene.evaluate(a, &rotationsA) == scene.evaluate(b, &rotationsB) && rotationsA == rotationsB;
}

}  // namespace

uint32_t demoReferenceThreads(bool cpuDevice) {
    if (cpuDevice) return 1;
    const uint32_t cores = std::thread::hardware_concurrency();
    return cores > 1 ? cores - 1 : 1;
}

DemoReference::DemoReference(uint32_t threads) : threads_(threads) {
    snapshot_.threads = threads;
    snapshot_.state = "waiting";
    worker_ = std::thread([this] { run(); });
}

DemoReference::~DemoReference() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
        cancel_ = true;  // the pass under way stops at its next row
    }
    wake_.notify_all();
    published_.notify_all();
    worker_.join();
}

bool DemoReference::update(const ReferenceRequest& request, bool lockstep) {
    // request_ is written only here, on this thread: read without the lock while the worker may run.
    ReferenceRequest wanted = request;
    if (request_.scene && request.scene == request_.scene &&
        samePose(*request.scene, request_.timeSeconds, request.timeSeconds))
        wanted.timeSeconds = request_.timeSeconds;  // nothing moved: the tracer goes on
    bool restarted = false;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        restarted =
            generation_ == 0 || !sameBuild(wanted, request_) || !sameCamera(wanted.camera, request_.camera);
        if (restarted) {
            request_ = std::move(wanted);
            ++generation_;
            cancel_ = true;  // a pass for the previous request is wasted work: stop it
            target_ = lockstep ? 1 : kMaxSamplesPerPixel;
        } else {
            target_ = lockstep ? std::min(target_ + 1, kMaxSamplesPerPixel) : kMaxSamplesPerPixel;
        }
    }
    wake_.notify_all();
    return restarted;
}

void DemoReference::waitForFrame() {
    std::unique_lock<std::mutex> lock(mutex_);
    published_.wait(lock, [&] {
        return quit_ || generation_ == 0 ||
               (publishedGeneration_ == generation_ && (workerSpp_ >= target_ || snapshot_.failed));
    });
}

ReferenceSnapshot DemoReference::snapshot() const {
    std::lock_guard<std::mutex> lock(mutex_);
    ReferenceSnapshot s = snapshot_;
    s.current = s.images && imagesGeneration_ == generation_;
    return s;
}

void DemoReference::publish(std::shared_ptr<const reference::ReferenceImages> images, uint64_t generation,
                            uint32_t spp, double raysPerSecond, const std::string& state, bool failed) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (images) {
            snapshot_.images = std::move(images);
            snapshot_.samplesPerPixel = spp;
            snapshot_.raysPerSecond = raysPerSecond;
            ++snapshot_.version;
            imagesGeneration_ = generation;
        }
        snapshot_.state = state;
        snapshot_.failed = failed;
        publishedGeneration_ = generation;
        workerSpp_ = spp;
    }
    published_.notify_all();
}

void DemoReference::run() {
    // Destroyed in reverse order: the tracer (which references the scene) before the scene.
    std::shared_ptr<const Scene> scene;
    std::unique_ptr<reference::PathTracer> tracer;
    ReferenceRequest built;   // what `tracer` traces
    uint64_t generation = 0;  // of `built`; 0: none (or a cancelled pass left partial sums: restart)
    bool failed = false;
    for (;;) {
        ReferenceRequest want;
        uint64_t wantGeneration = 0;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] {
                return quit_ || (generation_ != 0 && generation_ != generation) ||
                       (!failed && tracer && tracer->samplesPerPixel() < target_);
            });
            if (quit_) break;
            want = request_;
            wantGeneration = generation_;
            cancel_ = false;
        }
        if (wantGeneration != generation) {
            generation = wantGeneration;
            failed = false;
            try {
                if (!tracer || !sameBuild(want, built)) {
                    publish(nullptr, generation, 0, 0.0, "building the scene", false);
                    tracer.reset();  // the old tracer before the scene it references
                    scene = want.scene;
                    reference::ReferenceSettings settings;
                    settings.width = want.width;
                    settings.height = want.height;
                    settings.bounces = want.bounces;
                    settings.environment = want.environment;
                    settings.environmentMap = want.environmentMap;
                    settings.threads = threads_;
                    tracer = std::make_unique<reference::PathTracer>(*scene, want.timeSeconds, want.camera,
                                                                     settings);
                } else {
                    tracer->restart(want.camera);
                }
                built = want;
                publish(nullptr, generation, 0, 0.0, "tracing", false);
            } catch (const std::exception& e) {
                tracer.reset();
                scene.reset();
                failed = true;
                publish(nullptr, generation, 0, 0.0, std::string("failed: ") + e.what(), true);
            }
            continue;  // a newer request may be waiting already
        }
        try {
            const reference::ReferenceStats before = tracer->stats();
            if (!tracer->addSamples(1, {}, &cancel_)) {
                generation = 0;  // cancelled: the sums are partial, so whatever comes next restarts
                continue;
            }
            const reference::ReferenceStats& after = tracer->stats();
            const double seconds = after.seconds - before.seconds;
            const double rate = seconds > 0.0 ? double(after.rays - before.rays) / seconds : 0.0;
            const uint32_t spp = tracer->samplesPerPixel();
            auto images = std::make_shared<const reference::ReferenceImages>(tracer->images());
            publish(std::move(images), generation, spp, rate,
                    spp >= kMaxSamplesPerPixel ? "converged" : "tracing", false);
        } catch (const std::exception& e) {
            tracer.reset();
            scene.reset();
            failed = true;
            publish(nullptr, generation, 0, 0.0, std::string("failed: ") + e.what(), true);
        }
    }
    tracer.reset();
    scene.reset();
}

std::vector<uint8_t> referencePixels(const reference::ReferenceImages& images, AuxView view, float exposure) {
    const std::vector<glm::vec3>& source = view == AuxView::Direct     ? images.direct.mean
                                           : view == AuxView::Diffuse  ? images.diffuseIndirect.mean
                                           : view == AuxView::Specular ? images.specularIndirect.mean
                                                                       : images.final.mean;
    std::vector<uint8_t> bytes(source.size() * 4);
    for (size_t p = 0; p < source.size(); ++p) {
        const glm::vec3 c = glsl::linearToSrgb(glsl::toneMapAces(source[p], exposure));
        for (int k = 0; k < 3; ++k)
            bytes[4 * p + size_t(k)] =
                uint8_t(std::lround(std::clamp(std::isfinite(c[k]) ? c[k] : 0.0f, 0.0f, 1.0f) * 255.0f));
        bytes[4 * p + 3] = 255;
    }
    return bytes;
}

}  // namespace vct
