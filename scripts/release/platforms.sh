# SPDX-License-Identifier: GPL-3.0-or-later
# The release's platforms, sourced by the release scripts: what each one is built for.
#   platform_facts PLATFORM   sets zig_target, cmake_system, cmake_processor, meson_system,
#                             meson_cpu, wheel_platform (the wheel's platform tag) and
#                             blender_platform (the extension manifest's name for it)
release_platforms=(linux-x64)

platform_facts() {
  case "$1" in
    linux-x64)
      # glibc 2.28: the VFX Reference Platform's oldest Linux (Rocky/Alma 8), which official
      # Blender's Linux builds target too.
      zig_target=x86_64-linux-gnu.2.28
      cmake_system=Linux cmake_processor=x86_64
      meson_system=linux meson_cpu=x86_64
      wheel_platform=manylinux_2_28_x86_64
      blender_platform=linux-x64
      ;;
    *)
      echo "platforms.sh: unknown platform '$1' (known: ${release_platforms[*]})" >&2
      return 1
      ;;
  esac
}
