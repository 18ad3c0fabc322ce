// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Cancellation and progress shared between a running voxelization and other threads
// (the Blender add-on's modal timer reads .progress and calls .cancel()). Plain atomics:
// no GIL is needed to read or set them, and worker threads poll them without locks.
#include <atomic>

namespace hyvox::python {

class CancelToken {
public:
    void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
    void reset() {
        cancelled_.store(false, std::memory_order_relaxed);
        progress_.store(-1, std::memory_order_relaxed);
    }
    bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
    int progress() const { return progress_.load(std::memory_order_relaxed); }
    bool running() const { return running_.load(std::memory_order_relaxed) > 0; }

    // Worker threads report out of order; keep the highest percent seen.
    void raiseProgress(int percent) {
        int seen = progress_.load(std::memory_order_relaxed);
        while (percent > seen && !progress_.compare_exchange_weak(seen, percent, std::memory_order_relaxed)) {}
    }
    void begin() {
        progress_.store(0, std::memory_order_relaxed);
        running_.fetch_add(1, std::memory_order_relaxed);
    }
    void finish() { running_.fetch_sub(1, std::memory_order_relaxed); }

private:
    std::atomic<bool> cancelled_{false};
    std::atomic<int> progress_{-1};
    std::atomic<int> running_{0};
};

}  // namespace hyvox::python
