// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The GL passes of the `triangle`, `fragment` and `hybrid` methods over one uploaded mesh.
// Construct and use only inside gl::GlWorker::run (it owns GL objects).
//
// Grids whose bit volume exceeds one tile (gl/bit_tiles.h: a shader storage block, or
// GlOptions::tile_bytes) run tile by tile. Limits are checked before anything big is
// allocated.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/voxel_piece.h"
#include "gl/active_uniforms.h"
#include "gl/bit_tiles.h"
#include "gl/gl_objects.h"
#include "gl/gl_tuning.h"
#include "gl/gpu_mesh.h"
#include "gl/shader_library.h"
#include "hyvox/bit_grid.h"
#include "hyvox/grid.h"
#include "hyvox/options.h"

namespace hyvox::hybrid {

struct PassTimes {
    double pass1_gpu_ms = 0;            // compute: triangle-parallel, or hybrid classify + small triangles
    double pass2_gpu_ms = 0;            // rasterization: fragment-parallel, or hybrid's large triangles
    std::uint64_t large_triangles = 0;  // hybrid: triangles deferred to pass 2 (summed over tiles)
    double readback_ms = 0;
    double clip_gpu_ms = 0;  // attributes: clipping the triangle/voxel pairs (clip_pieces.comp)
    int tiles = 0;
};

class GlVoxelizer {
public:
    GlVoxelizer(const gl::GpuMesh& mesh, const GridSpec& grid, Mode mode, Method method, const std::string& shader_dir,
                gl::ProgramCache& programs, const gl::GlTuning& tuning, std::uint64_t tile_bytes,
                std::uint64_t pair_list_bytes = 0);

    // Runs every tile; writes bits into `out` (dims = grid dims) unless it is null (timing
    // runs). before_tile (optional) runs before each tile: a place to throw Cancelled.
    PassTimes run(double cutoff, BitGrid* out, const std::function<void()>& before_tile = {});

    // Section 3.5: the set voxels as a list (x, y, z), each once, in no particular order.
    std::vector<std::array<std::int32_t, 3>> runVoxelList(double cutoff, PassTimes* times = nullptr);

    // As run(), and also appends to `pieces` every (voxel, triangle) pair the passes find,
    // clipped on the GPU (shaders/hybrid/clip_pieces.comp), in no particular order. A tile
    // whose pairs overflow the list is run again with room for them all; one whose pairs
    // exceed a storage block, as its two halves.
    PassTimes runPieces(double cutoff, BitGrid* out, std::vector<VoxelPiece>& pieces,
                        const std::function<void()>& before_tile = {});

private:
    // What the voxelizing passes write besides the bit grid.
    enum class Output { Bits, VoxelList, AttributePairs };
    struct Programs {
        gl::ActiveProgram triangle, classify, raster, clip;
        bool built = false;
        // Calls set(program id) for each of the programs that uses uniform `location`.
        template <typename Set>
        void setUniform(GLint location, const Set& set) const {
            gl::setUniform({&triangle, &classify, &raster, &clip}, location, set);
        }
    };
    // Built on first use, then kept for this voxelizer's runs.
    const Programs& programsFor(Output output);
    // One tile's pairs into pairs_ (room for pair_capacity_, grown and run again until they
    // fit), then clipped into pieces_; returns the pair count, or nothing when the pairs of a
    // tile of several slabs exceed one storage block (run its halves instead).
    std::optional<std::uint32_t> runTilePairs(const Programs& programs, const gl::BitTile& tile, double cutoff,
                                              PassTimes& times);
    // One tile's passes into bits_ (its slab uniforms set before).
    void runTile(const Programs& programs, double cutoff, PassTimes& times);
    // runTile with the passes also appending to `list` (a 32-bit count, then entries) bound at
    // `binding`, with room for `capacity` entries. Returns the count the passes asked for
    // (over capacity: the rest was dropped, run again with more room); the GPU time goes to
    // `times` either way, the tile's counters to `attempt`.
    std::uint32_t runTileIntoList(const Programs& programs, double cutoff, gl::Buffer& list, GLuint binding,
                                  GLint capacity_location, std::uint32_t capacity, PassTimes& times,
                                  PassTimes& attempt);
    void setRunUniforms(const Programs& programs, double cutoff) const;  // the same for every tile
    void setTileUniforms(const Programs& programs, const gl::BitTile& tile) const;

    const GridSpec& grid_;
    Mode mode_;
    Method method_;
    std::string shader_dir_;
    gl::ProgramCache& programs_;
    std::uint32_t triangle_count_;
    gl::BitTiling tiling_;
    std::uint64_t pair_list_bytes_;  // GlOptions::pair_list_bytes (0 = the device's storage-block limit)
    Programs programs_by_output_[3];
    gl::Buffer vertices_, triangles_, bits_, large_, draw_, voxel_list_, pairs_, pieces_;
    std::uint32_t pair_capacity_ = 0;  // pairs pairs_ and pieces_ hold (kept across tiles)
    gl::VertexArray empty_vao_;
    gl::Framebuffer framebuffer_;
    gl::GlTuning tuning_;
    // llvmpipe only: per-triangle bounding-box side and projected area, for chunksFor().
    std::vector<float> extents_, areas_;
    // Compute work groups along z: chunks of the largest triangle pass 1 voxelizes.
    std::uint32_t chunksFor(double cutoff) const;
};

}  // namespace hyvox::hybrid
