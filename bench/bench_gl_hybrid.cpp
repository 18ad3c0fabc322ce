// SPDX-License-Identifier: GPL-3.0-or-later
// bench_gl_hybrid [--mesh-dir DIR] [--res N]... [--repeat R] [--mode conservative|thin]
//                 [--cutoff auto|X] [--device D] [--out DIR] [MESH... | triangle]
// The JCGT paper's Table 1 per mesh and resolution: triangle-parallel, fragment-parallel and
// hybrid @cutoff GPU times (pass 1 + pass 2, medians of R runs after a warm-up), the hybrid's
// pass 1 / pass 2 split and large-triangle count, its end-to-end wall time (voxelize():
// validation, upload, voxelize, readback) and the cpu backend's wall time beside them.
// "triangle" is the paper's scene-spanning single triangle. On Mesa's llvmpipe pass times
// come from the wall clock around glFinish (its timer queries miss compute work). The table
// also goes to DIR/gl_hybrid.{json,md} (default bench/results/).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <filesystem>
#include <fstream>

#include "bench_args.h"
#include "bench_results.h"
#include "core/stopwatch.h"
#include "gl/binding_points.h"
#include "gl/gl_debug.h"
#include "gl/gl_objects.h"
#include "gl/gl_worker.h"
#include "gl/gpu_mesh.h"
#include "gl/shader_library.h"
#include "hyvox/mesh_io.h"
#include "hyvox/voxelize.h"

namespace {

using hyvox::bench::median;

// The baseline the issue sets: one invocation per triangle, brute-force 13-axis SAT
// (Akenine-Moller) of every voxel in the triangle's bounding box. Bench-only, so it lives
// here rather than in shaders/.
const char* kNaiveShader = R"glsl(// SPDX-License-Identifier: GPL-3.0-or-later
#include "common/mesh_input.glsl"
#include "common/bit_output.glsl"
#include "common/compute_index.glsl"

bool separated(vec3 axis, vec3 a, vec3 b, vec3 c) {
    const float p0 = dot(axis, a), p1 = dot(axis, b), p2 = dot(axis, c);
    const float r = 0.5 * (abs(axis.x) + abs(axis.y) + abs(axis.z));
    return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

bool overlapsBox(vec3 centre, vec3 v0, vec3 v1, vec3 v2) {
    const vec3 a = v0 - centre, b = v1 - centre, c = v2 - centre;
    const vec3 e[3] = vec3[3](b - a, c - b, a - c);
    for (int i = 0; i < 3; ++i) {
        if (separated(vec3(0.0, -e[i].z, e[i].y), a, b, c)) return false;
        if (separated(vec3(e[i].z, 0.0, -e[i].x), a, b, c)) return false;
        if (separated(vec3(-e[i].y, e[i].x, 0.0), a, b, c)) return false;
    }
    if (separated(cross(e[0], e[1]), a, b, c)) return false;
    return true;  // the box axes: the loop runs over the bounding box only
}

void main() {
    const uint tri = invocationTriangle();
    if (tri >= triangleCount) return;
    ivec3 origin;
    vec3 v0, v1, v2;
    loadTriangle(tri, origin, v0, v1, v2);
    const ivec3 lo = max(clipLow(), ivec3(ceil(min(v0, min(v1, v2)))) - 1 + origin);
    const ivec3 hi = min(clipHigh(), ivec3(floor(max(v0, max(v1, v2)))) + origin);
    for (int x = lo.x; x <= hi.x; ++x)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int z = lo.z; z <= hi.z; ++z)
                if (overlapsBox(vec3(ivec3(x, y, z) - origin) + 0.5, v0, v1, v2)) setVoxel(ivec3(x, y, z), tri);
}
)glsl";

// Median GPU milliseconds of the naive shader (conservative), on the library's GL worker.
double naiveMs(const hyvox::MeshView& view, const hyvox::VoxelizeOptions& options, int repeat) {
    using namespace hyvox;
    const ValidatedMesh mesh = validate(view);
    const GridSpec grid = makeGrid(mesh.bounds, options.grid);
    const gl::GpuMesh gpu = gl::makeGpuMesh(mesh, grid);
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "hyvox_bench_naive";
    std::filesystem::create_directories(dir / "common");
    for (const auto& [name, text] : gl::embeddedShaders())
        if (name.rfind("common/", 0) == 0) std::ofstream(dir / name) << text;
    std::ofstream(dir / "naive.comp") << kNaiveShader;
    gl::GlWorker& worker = gl::GlWorker::get(options.gl.device);
    return worker.run([&] {
        const gl::Program program = gl::buildProgram(
            {{GL_COMPUTE_SHADER, "naive.comp"}},
            "#define HYVOX_THIN 0\n#define HYVOX_VOXEL_LIST 0\n#define HYVOX_ATTRIBUTE_PAIRS 0\n", dir.string());
        const gl::Buffer vertices(gpu.vertices.size() * sizeof(gl::GpuVertex), gpu.vertices.data(), 0);
        const gl::Buffer triangles(gpu.triangles.size() * 4, gpu.triangles.data(), 0);
        const gl::Buffer bits(grid.bricks().total() * BitGrid::kWordsPerBrick * sizeof(std::uint64_t), nullptr, 0);
        vertices.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_VERTICES);
        triangles.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_TRIANGLES);
        bits.bindBase(GL_SHADER_STORAGE_BUFFER, HYVOX_SSBO_BITS);
        glProgramUniform3i(program.id(), HYVOX_LOC_GRID_DIMS, grid.dims[0], grid.dims[1], grid.dims[2]);
        glProgramUniform2i(program.id(), HYVOX_LOC_SLAB, 0, grid.dims[0]);
        glProgramUniform1ui(program.id(), HYVOX_LOC_TRIANGLE_COUNT, GLuint(gpu.triangleCount()));
        program.use();
        const GLuint groups = GLuint((gpu.triangleCount() + HYVOX_LOCAL_SIZE - 1) / HYVOX_LOCAL_SIZE);
        std::vector<double> ms;
        for (int r = 0; r <= repeat; ++r) {  // run 0 warms up (llvmpipe compiles lazily)
            bits.clearToZero();
            glFinish();
            Stopwatch watch;
            glDispatchCompute(std::min<GLuint>(groups, 65535), (groups + 65534) / 65535, 1);
            glFinish();
            if (r) ms.push_back(watch.elapsedMs());
        }
        gl::checkGl("naive baseline");
        return median(ms);
    });
}

struct Sample {
    double gpu_ms = 0, pass1_ms = 0, pass2_ms = 0, wall_ms = 0, large = 0, cutoff = 0;
};

Sample runMedian(const hyvox::MeshView& mesh, const hyvox::VoxelizeOptions& options, int repeat) {
    hyvox::voxelize(mesh, options);  // warm-up: shader compilation, auto-cutoff search (cached)
    std::vector<double> gpu, pass1, pass2, wall;
    Sample s;
    for (int r = 0; r < repeat; ++r) {
        hyvox::Stopwatch watch;
        const hyvox::VoxelizeResult result = hyvox::voxelize(mesh, options);
        wall.push_back(watch.elapsedMs());
        const hyvox::HybridStats h = result.stats.hybrid.value_or(hyvox::HybridStats{});  // none for cpu
        gpu.push_back(h.pass1_gpu_ms + h.pass2_gpu_ms);
        pass1.push_back(h.pass1_gpu_ms);
        pass2.push_back(h.pass2_gpu_ms);
        s.large = double(h.large_triangles);
        s.cutoff = h.cutoff;
    }
    s.gpu_ms = median(gpu);
    s.pass1_ms = median(pass1);
    s.pass2_ms = median(pass2);
    s.wall_ms = median(wall);
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    std::string mesh_dir = HYVOX_BENCH_MESH_DIR;
    std::vector<int> resolutions;
    std::vector<std::string> meshes;
    int repeat = 5;
    std::string out_dir = HYVOX_BENCH_RESULTS_DIR;
    hyvox::VoxelizeOptions options;
    options.hybrid.cutoff = -1.0;
    hyvox::bench::readEnvironment(options);
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        auto next = [&] { return hyvox::bench::optionValue(argc, argv, a); };
        if (arg == "--mesh-dir")
            mesh_dir = next();
        else if (arg == "--res")
            resolutions.push_back(std::atoi(next().c_str()));
        else if (arg == "--repeat")
            repeat = std::max(1, std::atoi(next().c_str()));
        else if (arg == "--mode")
            options.mode = hyvox::parseMode(next());
        else if (arg == "--device")
            options.gl.device = next();
        else if (arg == "--out")
            out_dir = next();
        else if (arg == "--cutoff") {
            const std::string v = next();
            options.hybrid.cutoff = v == "auto" ? -1.0 : std::atof(v.c_str());
        } else if (arg == "--help" || arg == "-h") {
            std::printf(
                "usage: bench_gl_hybrid [--mesh-dir DIR] [--res N]... [--repeat R] [--mode M] [--cutoff auto|X] "
                "[--device D] [--out DIR] [MESH...|triangle]\n");
            return 0;
        } else
            meshes.push_back(arg);
    }
    if (resolutions.empty()) resolutions = {128, 256, 512};
    if (meshes.empty())
        meshes = {"bunny_stanford_69k.ply", "dragon_stanford_871k.ply.gz", "happy_buddha_100k.ply",
                  "sponza_crytek_262k_vcolor.ply.gz", "triangle"};

    std::printf("%-20s %7s %4s | %8s | %9s %9s %9s %8s %6s %8s %8s | %8s %8s\n", "scene", "tris", "res", "naive",
                "triangle", "fragment", "hybrid", "cutoff", "large", "pass1", "pass2", "hyb wall", "cpu wall");
    hyvox::bench::ResultTable table(
        "gl_hybrid", std::string("The GL methods: the JCGT 2013 Table 1 columns, ") + hyvox::toString(options.mode),
        {{"scene"},
         {"triangles"},
         {"res"},
         {"naive ms", 2},
         {"triangle ms", 2},
         {"fragment ms", 2},
         {"hybrid ms", 2},
         {"hybrid cutoff", 2},
         {"large triangles"},
         {"pass 1 ms", 2},
         {"pass 2 ms", 2},
         {"hybrid wall ms", 2},
         {"cpu wall ms", 2}},
        argc, argv);
    table.setGpu(hyvox::bench::glDevicesText());
    table.note("GPU milliseconds (pass 1 + pass 2), medians of " + std::to_string(repeat) +
               " runs after a warm-up; naive: one invocation per triangle, brute-force SAT over its bounding box "
               "(conservative only); walls: whole voxelize() calls. On llvmpipe the passes are timed by the wall "
               "clock around glFinish.");
    for (const std::string& name : meshes) {
        hyvox::Mesh mesh;
        if (name == "triangle") {
            mesh.positions = {0.0f, 0.0f, 0.0f, 1.0f, 0.37f, 0.11f, 0.23f, 1.0f, 0.91f};
            mesh.triangles = {0, 1, 2};
        } else {
            mesh = hyvox::readMesh(name.find('/') == std::string::npos ? mesh_dir + "/" + name : name);
        }
        for (int res : resolutions) {
            options.grid.resolution = res;
            auto with = [&](hyvox::Method method) {
                hyvox::VoxelizeOptions o = options;
                o.method = method;
                return runMedian(mesh.view(), o, repeat);
            };
            const Sample triangle = with(hyvox::Method::Triangle);
            const Sample fragment = with(hyvox::Method::Fragment);
            const Sample hybrid = with(hyvox::Method::Hybrid);
            const Sample cpu = with(hyvox::Method::Cpu);
            const double naive =
                options.mode == hyvox::Mode::Conservative ? naiveMs(mesh.view(), options, repeat) : 0.0;
            std::printf("%-20s %7zu %4d | %8.2f | %9.2f %9.2f %9.2f %8.2f %6.0f %8.2f %8.2f | %8.2f %8.2f\n",
                        name.substr(0, name.find('.')).c_str(), mesh.triangleCount(), res, naive, triangle.gpu_ms,
                        fragment.gpu_ms, hybrid.gpu_ms, hybrid.cutoff, hybrid.large, hybrid.pass1_ms, hybrid.pass2_ms,
                        hybrid.wall_ms, cpu.wall_ms);
            std::fflush(stdout);
            table.add({name.substr(0, name.find('.')), mesh.triangleCount(), res,
                       options.mode == hyvox::Mode::Conservative ? hyvox::bench::Cell(naive) : hyvox::bench::Cell(),
                       triangle.gpu_ms, fragment.gpu_ms, hybrid.gpu_ms, hybrid.cutoff, std::int64_t(hybrid.large),
                       hybrid.pass1_ms, hybrid.pass2_ms, hybrid.wall_ms, cpu.wall_ms});
        }
    }
    std::printf(
        "(ms; medians of %d runs. naive = one invocation per triangle, brute-force SAT over its\n"
        " bounding box; GPU columns are pass 1 + pass 2; walls are whole voxelize() calls)\n",
        repeat);
    table.write(out_dir);
    return 0;
}
