// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A triangle's attribute values at a point of it, as a method that computes attributes itself
// (the tessellation, at its points' corners) asks for them through its BackendJob
// (core/backends.h). The exact definition behind it is attributes::SurfaceValues, which the
// dispatcher makes; the contract names no type of a layer above core.
#include <array>
#include <cstdint>

#include "hyvox/attribute_grid.h"

namespace hyvox {

class AttributeEvaluator {
public:
    virtual ~AttributeEvaluator() = default;

    // The channels evaluate() writes (values empty).
    virtual const AttributeGrid& layout() const = 0;
    int channels() const { return layout().channels(); }

    // The attributes of `triangle` (an index into the mesh's triangles) at barycentrics
    // `bary`; `unit_normal` is its geometric normal, used where the mesh has no per-vertex or
    // per-face normals. Writes channels() values. Thread-safe (const, no state).
    virtual void evaluate(std::uint32_t triangle, const std::array<double, 3>& bary,
                          const std::array<double, 3>& unit_normal, double* out) const = 0;

protected:
    AttributeEvaluator() = default;
    AttributeEvaluator(const AttributeEvaluator&) = default;
    AttributeEvaluator& operator=(const AttributeEvaluator&) = default;
};

}  // namespace hyvox
