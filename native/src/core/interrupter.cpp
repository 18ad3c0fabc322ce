// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/interrupter.h"

#include "hyvox/errors.h"

namespace hyvox {

void throwIfInterrupted(Interrupter* interrupter, int percent) {
    if (interrupter && interrupter->wasInterrupted(percent)) throw Cancelled();
}

}  // namespace hyvox
