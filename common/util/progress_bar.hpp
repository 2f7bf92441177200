#pragma once
// A progress bar on stderr for long CPU jobs (atmosphere tables): redrawn in place on a
// terminal, logged at 25 % steps otherwise (so logs of headless slaves stay readable).
// Thread-safe: workers call advance() from any thread.
#include <atomic>
#include <mutex>
#include <string>

namespace cupola {

class ProgressBar {
public:
    ProgressBar(std::string label, long total);
    ~ProgressBar();
    void advance(long n = 1);
    void finish();

private:
    void draw(long done);
    std::string label_;
    long total_;
    std::atomic<long> done_{0};
    std::mutex mutex_;
    int last_drawn_ = -1;  // per cent (tty) or quarter (log)
    bool tty_;
    bool finished_ = false;
};

}  // namespace cupola
