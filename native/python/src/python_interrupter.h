// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The Interrupter the module hands to native work (voxelize, write_vdb): a CancelToken that
// any thread may cancel, and an optional Python progress callback.
#include <atomic>
#include <exception>
#include <memory>
#include <thread>

#include "bindings.h"
#include "cancel_token.h"
#include "hyvox/interrupter.h"

namespace hyvox::python {

// Feeds the CancelToken from worker threads (atomics only) and calls the Python progress
// callback on the calling thread alone, taking the GIL just for the call. A callback that
// raises stops the voxelization; its exception is re-raised once native code has returned.
class PythonInterrupter final : public Interrupter {
public:
    PythonInterrupter(std::shared_ptr<CancelToken> token, py::object progress)
        : token_(std::move(token)),
          progress_(std::move(progress)),
          has_progress_(!progress_.is_none()),
          caller_(std::this_thread::get_id()) {}

    void start(const char*) override {
        if (token_) token_->begin();
    }
    void end() override {
        if (token_) token_->finish();
    }
    bool wasInterrupted(int percent) override {
        if (percent >= 0 && token_) token_->raiseProgress(percent);
        if (std::this_thread::get_id() == caller_ && percent > reported_ && has_progress_ && !failed_.load()) {
            reported_ = percent;
            py::gil_scoped_acquire acquire;
            try {
                progress_(percent);
            } catch (py::error_already_set&) {
                error_ = std::current_exception();
                failed_.store(true);
            }
        }
        return failed_.load(std::memory_order_relaxed) || (token_ && token_->cancelled());
    }
    // Called with the GIL held, after the native call.
    void rethrowCallbackError() {
        if (error_) {
            std::exception_ptr error = std::move(error_);
            error_ = nullptr;
            std::rethrow_exception(error);
        }
    }

private:
    std::shared_ptr<CancelToken> token_;
    py::object progress_;
    bool has_progress_;
    std::thread::id caller_;
    int reported_ = -1;  // touched by the calling thread only
    std::atomic<bool> failed_{false};
    std::exception_ptr error_;
};

}  // namespace hyvox::python
