// SPDX-License-Identifier: GPL-3.0-or-later
// Built with -fno-math-errno -fno-trapping-math (solid/CMakeLists.txt): sqrt may then become
// one vector instruction and the selects may compute both sides, which the loop over the
// sheets needs to be vectorised (-fopt-info-vec reports it).
#include "solid/sheet_sum.h"

#include <algorithm>
#include <cmath>

#include "core/avx2_clones.h"
#include "solid/float_arctangent.h"

namespace hyvox::solid {
namespace {

constexpr std::size_t kLanes = 8;  // the sheets are padded to a multiple of this
constexpr double kTwoPi = 2.0 * M_PI;
constexpr float kTie = SheetSum::kTie;

// The sheet (b, a, a + ∞z, b + ∞z) (up -1: to -∞z) subtends the solid angle of the spherical
// triangle of the directions to b, to a and up (down): by van Oosterom & Strackee,
// Ω/2 = atan2(up (u × v)_z, |u||v| + u·v + up (|u| v_z + |v| u_z)) with u = b - q, v = a - q.
// Written for float: (u × v)_z = (e × w)_z with w the shorter of u and v, and the second
// argument = s_u s_v + u_xy · v_xy with s = |u| + up u_z, which is (u_x² + u_y²) / (|u| - up u_z)
// where up u_z < 0 (no cancellation, however far above the edge q lies).
//
// What of a sheet's term depends on q's x and y alone (at() computes it per point, atColumn()
// once per vertical line): |u_xy|², |v_xy|², u_xy · v_xy, up (e × u)_z, up (e × v)_z, and NaN
// where the column passes within kTie of the edge in xy (the rays' tie-breaking decides there).
struct LineParts {
    float uxy2, vxy2, uv, eu, ev, poison;
};

inline LineParts lineParts(float up, float vx, float vy, float ex, float ey, float inverse_length2) {
    const float ux = vx + ex, uy = vy + ey;
    // The nearest point of the edge to q in xy, a + t e.
    const float t = std::min(std::max(-(vx * ex + vy * ey) * inverse_length2, 0.0f), 1.0f);
    const float dx = vx + t * ex, dy = vy + t * ey;
    return {ux * ux + uy * uy,        vx * vx + vy * vy,        ux * vx + uy * vy,
            up * (ex * uy - ey * ux), up * (ex * vy - ey * vx), dx * dx + dy * dy < kTie * kTie ? NAN : 0.0f};
}

// The sheet's term, weight · Ω / 4π (+ the poison), at v_z = a_z - q_z, from its line parts.
inline float sheetTerm(float up, float weight, float uxy2, float vxy2, float uv, float eu, float ev, float poison,
                       float vz, float ez) {
    const float uz = vz + ez;
    const float lu = std::sqrt(uxy2 + uz * uz), lv = std::sqrt(vxy2 + vz * vz);
    const float su = up * uz >= 0 ? lu + up * uz : uxy2 / (lu - up * uz);
    const float sv = up * vz >= 0 ? lv + up * vz : vxy2 / (lv - up * vz);
    const float det = lu < lv ? eu : ev;
    return weight * floats::arctangent2(det, su * sv + uv) + poison;
}

// The terms summed in kLanes float lanes, then the lanes in double (n a multiple of kLanes).
inline double laneSum(const float* terms, std::size_t n) {
    float lanes[kLanes] = {};
    for (std::size_t i = 0; i < n; i += kLanes)
        for (std::size_t j = 0; j < kLanes; ++j) lanes[j] += terms[i + j];
    double sum = 0;
    for (const float lane : lanes) sum += lane;
    return sum;
}

}  // namespace

void SheetSum::assign(const std::vector<GradientBound::Sheet>& sheets, bool upward,
                      const std::array<double, 3>& origin) {
    count_ = sheets.size();
    up_ = upward ? -1.0f : 1.0f;
    origin_ = origin;
    const std::size_t padded = (count_ + kLanes - 1) / kLanes * kLanes;
    for (auto* array : {&ax_, &ay_, &az_, &ex_, &ey_, &ez_, &inverse_length2_, &weight_}) array->assign(padded, 0.0f);
    for (std::size_t i = 0; i < count_; ++i) {
        const GradientBound::Sheet& s = sheets[i];
        const double ex = s.b[0] - s.a[0], ey = s.b[1] - s.a[1];
        ax_[i] = float(s.a[0] - origin[0]);
        ay_[i] = float(s.a[1] - origin[1]);
        az_[i] = float(s.a[2] - origin[2]);
        ex_[i] = float(ex);
        ey_[i] = float(ey);
        ez_[i] = float(s.b[2] - s.a[2]);
        const double length2 = ex * ex + ey * ey;
        inverse_length2_[i] = length2 > 0 ? float(1.0 / length2) : 0.0f;
        weight_[i] = float(s.excess / kTwoPi);
    }
    // Padding: an edge of length 0 far away (finite terms, never near), weight 0.
    for (std::size_t i = count_; i < padded; ++i) ax_[i] = ay_[i] = 1e6f;
    terms_.resize(padded);
    for (auto* array : {&uxy2_, &vxy2_, &uv_, &eu_, &ev_, &poison_}) array->resize(padded);
}

// An AVX2 copy where the platform dispatches by processor (core/avx2_clones.h): eight floats a
// step instead of four.
HYVOX_AVX2_CLONES
double SheetSum::at(const std::array<double, 3>& point) const {
    const float qx = float(point[0] - origin_[0]), qy = float(point[1] - origin_[1]), qz = float(point[2] - origin_[2]);
    const float up = up_;
    const std::size_t n = ax_.size();
    const float *ax = ax_.data(), *ay = ay_.data(), *az = az_.data(), *ex = ex_.data(), *ey = ey_.data(),
                *ez = ez_.data(), *inverse_length2 = inverse_length2_.data(), *weight = weight_.data();
    float* terms = terms_.data();
    for (std::size_t i = 0; i < n; ++i) {
        const LineParts l = lineParts(up, ax[i] - qx, ay[i] - qy, ex[i], ey[i], inverse_length2[i]);
        terms[i] = sheetTerm(up, weight[i], l.uxy2, l.vxy2, l.uv, l.eu, l.ev, l.poison, az[i] - qz, ez[i]);
    }
    return laneSum(terms, n);
}

HYVOX_AVX2_CLONES
void SheetSum::atColumn(double x, double y, const double* z, int count, double* out) const {
    const float qx = float(x - origin_[0]), qy = float(y - origin_[1]);
    const float up = up_;
    const std::size_t n = ax_.size();
    const float *ax = ax_.data(), *ay = ay_.data(), *az = az_.data(), *ex = ex_.data(), *ey = ey_.data(),
                *ez = ez_.data(), *inverse_length2 = inverse_length2_.data(), *weight = weight_.data();
    float *uxy2 = uxy2_.data(), *vxy2 = vxy2_.data(), *uv = uv_.data(), *eu = eu_.data(), *ev = ev_.data(),
          *poison = poison_.data();
    for (std::size_t i = 0; i < n; ++i) {
        const LineParts l = lineParts(up, ax[i] - qx, ay[i] - qy, ex[i], ey[i], inverse_length2[i]);
        uxy2[i] = l.uxy2, vxy2[i] = l.vxy2, uv[i] = l.uv, eu[i] = l.eu, ev[i] = l.ev, poison[i] = l.poison;
    }
    float* terms = terms_.data();
    for (int k = 0; k < count; ++k) {
        const float qz = float(z[k] - origin_[2]);
        for (std::size_t i = 0; i < n; ++i)
            terms[i] = sheetTerm(up, weight[i], uxy2[i], vxy2[i], uv[i], eu[i], ev[i], poison[i], az[i] - qz, ez[i]);
        out[k] = laneSum(terms, n);
    }
}

}  // namespace hyvox::solid
