// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// GlWorker: one thread that owns one headless GL 4.5 context for the library's lifetime.
// Callers submit work with run() and wait for it; the work runs on the worker thread with
// the context current, so the caller's own GL/EGL state (Blender's) is never touched.
//
//   auto& worker = gl::GlWorker::get(options.gl.device);   // throws BackendError
//   int n = worker.run([&] { /* GL calls here */ return 42; });  // exceptions propagate
//
// Work items run one at a time in submission order. GL objects created inside run() must
// be destroyed inside run() too (the RAII types in gl_objects.h do that when they are
// locals of the work item, or live in the worker's cache).
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>

#include "gl/egl_device.h"

namespace hyvox::gl {

class ProgramCache;

class GlWorker {
public:
    // The worker for a device selection (GlOptions::device: "" = auto; see EglContext).
    // Made on first use and kept for the process lifetime; a failure to make the context is
    // thrown (BackendError) and not cached, so a later call may try again.
    static GlWorker& get(const std::string& device = "");

    template <typename F>
    auto run(F&& work) -> std::invoke_result_t<F&> {
        using R = std::invoke_result_t<F&>;
        auto task = std::make_shared<std::packaged_task<R()>>(std::forward<F>(work));
        std::future<R> done = task->get_future();
        post([task] { (*task)(); });
        return done.get();
    }

    const EglDeviceInfo& device() const { return device_; }
    const std::string& renderer() const { return renderer_; }
    // Compiled programs, keyed by stages + defines; use only inside run().
    ProgramCache& programs() { return *programs_; }

    GlWorker(const GlWorker&) = delete;
    GlWorker& operator=(const GlWorker&) = delete;

private:
    explicit GlWorker(const std::string& selection);
    void post(std::function<void()> work);
    void loop(const std::string& selection, std::promise<void>& ready);

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> queue_;
    std::thread thread_;
    EglDeviceInfo device_;
    std::string renderer_;
    std::unique_ptr<ProgramCache> programs_;
};

}  // namespace hyvox::gl
