#include "util/progress_bar.hpp"

#include <spdlog/spdlog.h>
#include <unistd.h>

#include <cstdio>

namespace cupola {

ProgressBar::ProgressBar(std::string label, long total)
    : label_(std::move(label)), total_(total > 0 ? total : 1), tty_(isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::advance(long n) { draw(done_.fetch_add(n) + n); }

void ProgressBar::finish() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
    if (tty_ && last_drawn_ >= 0) std::fputc('\n', stderr);
}

void ProgressBar::draw(long done) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    const int percent = static_cast<int>(100 * std::min(done, total_) / total_);
    if (tty_) {
        if (percent == last_drawn_) return;
        last_drawn_ = percent;
        const int width = 30, filled = percent * width / 100;
        std::fprintf(stderr, "\r%s [%s%s] %3d%%", label_.c_str(), std::string(filled, '#').c_str(),
                     std::string(width - filled, ' ').c_str(), percent);
        std::fflush(stderr);
    } else {
        const int quarter = percent / 25;
        if (quarter == last_drawn_) return;
        last_drawn_ = quarter;
        spdlog::info("{}: {}%", label_, quarter * 25);
    }
}

}  // namespace cupola
