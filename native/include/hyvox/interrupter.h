// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// @file
/// Progress and cancellation in the style of OpenVDB's util::NullInterrupter:
/// start() once, wasInterrupted(percent) at milestones and inside long loops, end() once.

namespace hyvox {

/// The caller's side of a long run: it hears the progress and may ask the run to stop.
/// Implementations must be thread-safe: worker threads call wasInterrupted() concurrently.
class Interrupter {
public:
    virtual ~Interrupter() = default;
    /// Called once when a run starts; `name` says which ("hyvox voxelize", "hyvox write").
    virtual void start(const char* /*name*/) {}
    /// Called once when the run ends, also when it throws.
    virtual void end() {}
    /// Asked at milestones and inside long loops, from any thread.
    /// @param percent 0-100 progress of the current run, or -1 when unknown
    /// @return true when the caller should stop as soon as it can (it then throws Cancelled)
    virtual bool wasInterrupted([[maybe_unused]] int percent = -1) { return false; }
};

/// Throws hyvox::Cancelled when `interrupter` (may be null) asks to stop.
/// @param interrupter asked with `percent`; null never stops
/// @param percent the progress to report, 0-100, or -1 when unknown
void throwIfInterrupted(Interrupter* interrupter, int percent = -1);

/// start() on construction and end() on destruction, also when the run throws.
class InterrupterRun {
public:
    /// Calls interrupter->start(name) unless `interrupter` is null.
    InterrupterRun(Interrupter* interrupter, const char* name) : interrupter_(interrupter) {
        if (interrupter_) interrupter_->start(name);
    }
    ~InterrupterRun() {
        if (interrupter_) interrupter_->end();
    }
    InterrupterRun(const InterrupterRun&) = delete;
    InterrupterRun& operator=(const InterrupterRun&) = delete;

private:
    Interrupter* interrupter_;
};

}  // namespace hyvox
