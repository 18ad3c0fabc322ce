// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/gl_worker.h"

#include <unistd.h>

#include <atomic>
#include <map>

#include "gl/gl_debug.h"
#include "gl/shader_library.h"
#include "hyvox/errors.h"

namespace hyvox::gl {
namespace {

// The process that made the first GL worker. A child forked after that has the parent's
// memory but none of its threads: the worker thread that owns the context is gone (work
// posted to it would wait forever), and the driver's own threads and locks were copied in
// whatever state they were in, so a new context there can hang as well. Such a child gets
// a clear error instead. Read before any lock: a lock held at fork time stays held.
std::atomic<pid_t> g_gl_process{0};

void refuseForkedChild() {
    const pid_t parent = g_gl_process.load();
    if (parent == 0 || parent == ::getpid()) return;
    throw BackendError("the GL methods cannot run in a process forked from one that had already used GL (process " +
                       std::to_string(parent) +
                       "): its GL context and thread stay in that process. Start worker processes before the "
                       "first GL voxelization, or with multiprocessing's 'spawn' or 'forkserver' start method, "
                       "or use the cpu method here");
}

}  // namespace

GlWorker& GlWorker::get(const std::string& device) {
    // Workers are deliberately never destroyed: their threads own contexts until the process
    // ends, and tearing GL down from static destructors races the driver's own atexit hooks.
    static std::mutex registry_mutex;
    static auto* registry = new std::map<std::string, GlWorker*>();
    refuseForkedChild();
    const std::string selection = device.empty() ? "auto" : device;  // one worker for both spellings
    std::lock_guard<std::mutex> lock(registry_mutex);
    auto found = registry->find(selection);
    if (found != registry->end()) return *found->second;
    // Set before the first context is made: a fork while it is being made is refused too.
    pid_t none = 0;
    g_gl_process.compare_exchange_strong(none, ::getpid());
    auto* worker = new GlWorker(selection);  // throws if no context could be made
    registry->emplace(selection, worker);
    return *worker;
}

GlWorker::GlWorker(const std::string& selection) {
    std::promise<void> ready;
    auto started = ready.get_future();
    // The promise moves into the thread, so nothing it touches dies with this constructor.
    thread_ = std::thread([this, selection, promise = std::move(ready)]() mutable { loop(selection, promise); });
    try {
        started.get();
    } catch (...) {
        thread_.join();
        throw;
    }
    thread_.detach();  // lives as long as the process; see get()
}

void GlWorker::post(std::function<void()> work) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        queue_.push_back(std::move(work));
    }
    wake_.notify_one();
}

void GlWorker::loop(const std::string& selection, std::promise<void>& ready) {
    std::unique_ptr<EglContext> context;
    try {
        context = std::make_unique<EglContext>(selection);
        enableDebugOutput();
        device_ = context->device();
        renderer_ = context->renderer();
        programs_ = std::make_unique<ProgramCache>();
    } catch (...) {
        ready.set_exception(std::current_exception());
        return;
    }
    ready.set_value();
    for (;;) {
        std::function<void()> work;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return !queue_.empty(); });
            work = std::move(queue_.front());
            queue_.pop_front();
        }
        work();  // a packaged_task: exceptions travel to the caller's future
    }
}

}  // namespace hyvox::gl
