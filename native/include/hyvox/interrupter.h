// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Progress and cancellation in the style of OpenVDB's util::NullInterrupter:
// start() once, wasInterrupted(percent) at milestones and inside long loops, end() once.
// Implementations must be thread-safe: worker threads call wasInterrupted concurrently.

namespace hyvox {

class Interrupter {
public:
    virtual ~Interrupter() = default;
    virtual void start(const char* /*name*/) {}
    virtual void end() {}
    // percent: 0-100 progress of the current run, or -1 when unknown.
    // Returns true when the caller should stop as soon as it can.
    virtual bool wasInterrupted(int /*percent*/ = -1) { return false; }
};

// Throws hyvox::Cancelled when the interrupter (may be null) asks to stop.
void throwIfInterrupted(Interrupter* interrupter, int percent = -1);

// start() on construction and end() on destruction, also when the run throws.
class InterrupterRun {
public:
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
