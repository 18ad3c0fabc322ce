// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/gl_devices.h"

#include "gl/egl_device.h"

namespace hyvox {

std::vector<GlDevice> listGlDevices() {
    std::vector<GlDevice> out;
    for (const auto& d : gl::listEglDevices()) out.push_back({d.index, d.name, d.software});
    return out;
}

}  // namespace hyvox
