/* SPDX-License-Identifier: GPL-3.0-or-later */
/* The CPU model that the resolvers of HYVOX_AVX2_CLONES functions read (core/avx2_clones.h),
 * for a toolchain whose runtime has none (zig's; GCC's libgcc and LLVM's compiler-rt have it):
 * the same names and layout, and the two feature bits the resolvers ask for, AVX (9) and AVX2
 * (10) of the first feature word, set only where the processor has them and the system saves
 * the AVX registers (XGETBV). Built only where CMakeLists.txt finds the runtime's missing. */
#include <cpuid.h>

struct hyvox_processor_model {
    unsigned int vendor, type, subtype;
    unsigned int features[1];
};
struct hyvox_processor_model __cpu_model;

int __cpu_indicator_init(void) {
    unsigned int a, b, c, d, leaf7_b = 0, xcr0 = 0, high = 0;
    if (__cpu_model.vendor) return 0;
    __cpu_model.vendor = 4; /* "other": what it is does not matter here */
    if (!__get_cpuid(1, &a, &b, &c, &d)) return 0;
    const int osxsave = (c >> 27) & 1, avx = (c >> 28) & 1;
    if (osxsave) __asm__("xgetbv" : "=a"(xcr0), "=d"(high) : "c"(0));
    if (!avx || !osxsave || (xcr0 & 6) != 6) return 0;
    __cpu_model.features[0] |= 1u << 9;
    if (__get_cpuid_count(7, 0, &a, &leaf7_b, &c, &d) && ((leaf7_b >> 5) & 1)) __cpu_model.features[0] |= 1u << 10;
    return 0;
}
