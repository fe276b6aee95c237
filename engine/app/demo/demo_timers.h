// The demo's timer overlay data: per-pass GPU times of the last frames (Renderer's GpuTimer::lastFrame) as
// rolling medians, and the frame-time history the graph draws. Free of ImGui: unit-tested.
#pragma once

#include <deque>
#include <string>
#include <utility>
#include <vector>

namespace vct {

class RollingTimers {
  public:
    explicit RollingTimers(size_t window = 60) : window_(window) {}

    // One frame's (pass, ms) list; passes keep the order they first appeared in. A pass missing from a frame
    // (a configuration without it) ages out after `window` frames.
    void add(const std::vector<std::pair<std::string, double>>& frame);
    void clear();

    struct Bar {
        std::string name;
        double medianMs = 0.0;
    };
    // Median per pass over the frames in the window that had it.
    std::vector<Bar> medians() const;
    // Median of the per-frame sums (the GPU frame).
    double frameMedianMs() const;
    size_t frames() const { return frames_.size(); }

  private:
    size_t window_;
    std::deque<std::vector<std::pair<std::string, double>>> frames_;
};

// A fixed-length history of values (frame times), oldest first, for a line graph.
class History {
  public:
    explicit History(size_t length = 120) : length_(length) {}
    void push(float value);
    const std::vector<float>& values() const { return values_; }
    float max() const;

  private:
    size_t length_;
    std::vector<float> values_;
};

double median(std::vector<double> values);

}  // namespace vct
