#include "app/demo/demo_timers.h"

#include <algorithm>

namespace vct {

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const size_t mid = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(mid), values.end());
    double m = values[mid];
    if (values.size() % 2 == 0)
        m = 0.5 * (m + *std::max_element(values.begin(), values.begin() + std::ptrdiff_t(mid)));
    return m;
}

void RollingTimers::add(const std::vector<std::pair<std::string, double>>& frame) {
    frames_.push_back(frame);
    while (frames_.size() > window_) frames_.pop_front();
}

void RollingTimers::clear() {
    frames_.clear();
}

std::vector<RollingTimers::Bar> RollingTimers::medians() const {
    std::vector<std::string> order;
    std::vector<std::vector<double>> samples;
    for (const auto& frame : frames_) {
        for (const auto& [name, ms] : frame) {
            auto it = std::find(order.begin(), order.end(), name);
            if (it == order.end()) {
                order.push_back(name);
                samples.emplace_back();
                it = order.end() - 1;
            }
            samples[size_t(it - order.begin())].push_back(ms);
        }
    }
    std::vector<Bar> bars;
    for (size_t i = 0; i < order.size(); ++i) bars.push_back({order[i], median(samples[i])});
    return bars;
}

double RollingTimers::frameMedianMs() const {
    std::vector<double> sums;
    for (const auto& frame : frames_) {
        double sum = 0.0;
        for (const auto& entry : frame) sum += entry.second;
        sums.push_back(sum);
    }
    return median(std::move(sums));
}

void History::push(float value) {
    values_.push_back(value);
    if (values_.size() > length_) values_.erase(values_.begin());
}

float History::max() const {
    return values_.empty() ? 0.0f : *std::max_element(values_.begin(), values_.end());
}

}  // namespace vct
