// SPDX-License-Identifier: GPL-3.0-or-later
// bench_device: the GL methods on the paper's Table 1 scenes in one process, for a lent GPU
// (bench/device/README.md). For each step of --order (MODE@RES, most important first) and
// each scene of --scenes it runs cpu (the oracle), hybrid (auto cutoff), triangle, fragment
// and, once per scene and resolution, tessellation; it writes one CSV row per method and
// flushes it, so a run cut short still leaves every finished row. Checks against the cpu
// voxels of the same mode: the exact methods must give the same voxel set ("equal"), or
// differ only by a few touches within 1e-5 voxel, as the tests accept ("touches"), else
// "DIFF"; tessellation gets its bias against the conservative and thin cpu voxels and its
// false voxels (voxels the conservative set lacks, which must be 0). An `attributes@RES` step
// times each exact method's binary run and its attribute run (colour where the scene has
// colours, and normals; conservative) and checks the values against cpu's. A `live@RES` step
// (issue 29) times what a live volume's worker does per edit, without Blender: a vertex moved,
// the grid on the lattice fixed in world space, voxelize, write the .vdb that Blender loads.
//
//   bench_device --mesh-dir DIR --csv FILE [--info FILE] [--order thin@256,thin@512,...]
//                [--scenes bunny_stanford_69k.ply,...,dragon_stanford_871k.ply.gz:x16,triangle]
//                [--repeat 5] [--row-budget-s 3] [--budget-s 300] [--device D] [--require-hardware]
//
// A scene "FILE:x4" / "FILE:x16" is FILE midpoint-subdivided once / twice (dense stand-ins
// for the paper's 7.2M-triangle Asian Dragon); "triangle" is the paper's scene-spanning
// single triangle. Each method runs once to warm up (shaders, the hybrid's cutoff search,
// which is cached per mesh and grid), then up to --repeat times, fewer when the warm-up took
// long (each row aims at --row-budget-s); GPU columns are medians of the GL timer queries
// (pass times; the wall clock around glFinish on llvmpipe), wall_ms the median whole
// voxelize() call. No step starts after --budget-s seconds.
#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "bench_args.h"
#include "core/stopwatch.h"
#include "gl/gl_worker.h"
#include "hyvox/accuracy.h"
#include "hyvox/attribute_grid.h"
#include "hyvox/errors.h"
#include "hyvox/gl_devices.h"
#include "hyvox/mesh_io.h"
#include "hyvox/vdb.h"
#include "hyvox/voxelize.h"
#include "support/subdivide.h"
#include "support/voxel_checks.h"

namespace {

using hyvox::bench::median;
using hyvox::bench::splitList;

struct Step {
    hyvox::Mode mode = hyvox::Mode::Conservative;
    int resolution = 0;
    bool threads = false;     // "threads@RES": the cpu method's thread scaling
    bool attributes = false;  // "attributes@RES": the price of colour and normal voxels
    bool live = false;        // "live@RES": Live's updates (edit, voxelize, write) per second
};

// "thin@256" -> {Thin, 256}; "threads@512"; a bad step ends the program (a usage error).
Step parseStep(const std::string& text) {
    const auto at = text.find('@');
    const int res = at == std::string::npos ? 0 : std::atoi(text.c_str() + at + 1);
    if (res <= 0) {
        std::fprintf(stderr,
                     "bad --order step '%s' (want MODE@RES, threads@RES, attributes@RES or live@RES, e.g. thin@256)\n",
                     text.c_str());
        std::exit(2);
    }
    Step step;
    step.resolution = res;
    if (text.substr(0, at) == "threads")
        step.threads = true;
    else if (text.substr(0, at) == "attributes")
        step.attributes = true;
    else if (text.substr(0, at) == "live")
        step.live = true;
    else
        step.mode = hyvox::parseMode(text.substr(0, at));
    return step;
}

// Scenes are read (and subdivided) when first needed and then kept: a run cut short by the
// budget never pays for the 14M-triangle dragon it did not reach.
class Scenes {
public:
    explicit Scenes(std::string mesh_dir) : mesh_dir_(std::move(mesh_dir)) {}

    const hyvox::Mesh& get(const std::string& spec) {
        auto found = cache_.find(spec);
        if (found != cache_.end()) return *found->second;
        auto mesh = std::make_unique<hyvox::Mesh>();
        const auto colon = spec.rfind(":x");
        if (spec == "triangle") {
            mesh->positions = {0.0f, 0.0f, 0.0f, 1.0f, 0.37f, 0.11f, 0.23f, 1.0f, 0.91f};
            mesh->triangles = {0, 1, 2};
        } else if (colon != std::string::npos) {
            // x16 is x4 subdivided once more, so x4 is made (and kept) on the way.
            const int factor = std::atoi(spec.c_str() + colon + 2);
            const std::string base = spec.substr(0, colon);
            if (factor != 4 && factor != 16) throw hyvox::InvalidInput("scene '" + spec + "': only :x4 and :x16");
            const hyvox::Mesh& coarser = factor == 4 ? get(base) : get(base + ":x4");
            hyvox::Stopwatch watch;
            *mesh = hyvox::test::midpointSubdivide(coarser.view(), 1);
            std::printf("# subdivided %s: %zu triangles in %.0f ms\n", spec.c_str(), mesh->triangleCount(),
                        watch.elapsedMs());
        } else {
            *mesh = hyvox::readMesh(spec.find('/') == std::string::npos ? mesh_dir_ + "/" + spec : spec);
        }
        return *cache_.emplace(spec, std::move(mesh)).first->second;
    }

private:
    std::string mesh_dir_;
    std::map<std::string, std::unique_ptr<hyvox::Mesh>> cache_;
};

// The short name of a scene for the CSV: the file name without extensions, plus " x4".
std::string sceneName(const std::string& spec) {
    const auto colon = spec.rfind(":x");
    std::string file = spec.substr(0, colon);
    file = file.substr(file.find_last_of('/') + 1);
    file = file.substr(0, file.find('.'));
    return colon == std::string::npos ? file : file + " " + spec.substr(colon + 1);
}

// One method's timed runs: medians of the GPU passes, of the method's own stages and of the
// whole call.
struct Row {
    int runs = 0;
    int threads = 0;      // CPU threads asked for (0 = all cores)
    double first_ms = 0;  // the warm-up call (shader compilation, the hybrid's cutoff search)
    double wall_ms = 0, stage_ms = 0, gpu_ms = 0, pass0_ms = 0, pass1_ms = 0, pass2_ms = 0;
    hyvox::VoxelizeResult last;  // the last run's result (voxels and stats)
    std::string error;
};

double gpuPasses(const hyvox::Stats& s, double& p0, double& p1, double& p2) {
    p0 = p1 = p2 = 0;
    if (s.hybrid) {
        p1 = s.hybrid->pass1_gpu_ms;
        p2 = s.hybrid->pass2_gpu_ms;
    } else if (s.tessellation) {
        p0 = s.tessellation->pass0_gpu_ms;
        p1 = s.tessellation->pass1_gpu_ms;
        p2 = s.tessellation->pass2_gpu_ms;
    }
    return p0 + p1 + p2;
}

// The method's own stages: everything but validation, grid allocation, compaction and
// counting, which every method shares (as bench_tessellation counts them).
double methodStagesMs(const hyvox::Stats& s) {
    double ms = 0;
    for (const auto& [stage, t] : s.timings_ms)
        if (stage != "validate" && stage != "allocate" && stage != "compact" && stage != "count" && stage != "tiles")
            ms += t;
    return ms;
}

// A warm-up call, then timed calls: as many as fit in row_budget_ms by the first timed
// call's length, at least 1 and at most `repeat`.
Row timeMethod(const hyvox::Mesh& mesh, const hyvox::VoxelizeOptions& options, int repeat, double row_budget_ms) {
    Row row;
    row.threads = options.threads;
    try {
        hyvox::Stopwatch first;
        row.last = hyvox::voxelize(mesh.view(), options);
        row.first_ms = first.elapsedMs();
        std::vector<double> wall, stage, gpu, p0, p1, p2;
        for (int r = 0; r < repeat; ++r) {
            hyvox::Stopwatch watch;
            row.last = hyvox::voxelize(mesh.view(), options);
            wall.push_back(watch.elapsedMs());
            stage.push_back(methodStagesMs(row.last.stats));
            double a, b, c;
            gpu.push_back(gpuPasses(row.last.stats, a, b, c));
            p0.push_back(a);
            p1.push_back(b);
            p2.push_back(c);
            if (r == 0) repeat = std::clamp(int(row_budget_ms / std::max(wall[0], 1e-3)), 1, repeat);
        }
        row.runs = int(wall.size());
        row.wall_ms = median(wall);
        row.stage_ms = median(stage);
        row.gpu_ms = median(gpu);
        row.pass0_ms = median(p0);
        row.pass1_ms = median(p1);
        row.pass2_ms = median(p2);
    } catch (const std::exception& e) {
        row.error = e.what();
    }
    return row;
}

// "name=ms;..." of the stages of one call, for reading where the wall time goes.
std::string stageText(const hyvox::Stats& s) {
    std::string text;
    char buf[96];
    for (const auto& [stage, ms] : s.timings_ms) {
        std::snprintf(buf, sizeof buf, "%s%s=%.2f", text.empty() ? "" : ";", stage.c_str(), ms);
        text += buf;
    }
    return text;
}

// CSV text with no commas or quotes (error messages).
std::string field(std::string text) {
    for (char& c : text)
        if (c == ',' || c == '"' || c == '\n') c = ' ';
    return text;
}

// What a row was checked against and found.
struct Checked {
    std::string check = "-";  // equal | touches | DIFF | bias | - (not checked)
    std::uint64_t ref_voxels = 0, missed = 0, false_voxels = 0, touches = 0, unexplained = 0;
    double bias = -1, bias_thin = -1;  // -1: not measured
    // Attribute rows: the same method's binary run, and the largest difference of a colour
    // channel from cpu's values on the voxels both hold (-1: not measured).
    double binary_wall_ms = -1, attr_max_diff = -1;
};

// A GL method's voxels against cpu's of the same mode: the same set ("equal"), or differing
// only by touches within 1e-5 voxel, and few of them, as the tests accept ("touches").
Checked againstCpu(const hyvox::Mesh& mesh, hyvox::Mode mode, const hyvox::VoxelizeResult& result,
                   const hyvox::VoxelizeResult& cpu) {
    Checked c;
    c.ref_voxels = cpu.stats.voxel_count;
    if (result.occupancy == cpu.occupancy) {
        c.check = "equal";
        return c;
    }
    const hyvox::test::Comparison cmp = hyvox::test::compareResults(mesh.view(), mode, result, cpu);
    c.missed = cmp.oracle_only;
    c.false_voxels = cmp.result_only;
    c.touches = cmp.touches;
    c.unexplained = cmp.unexplained.size();
    const bool rare = cmp.touches <= std::max<std::uint64_t>(10, cmp.oracle_voxels / 10000);
    c.check = cmp.unexplained.empty() && rare ? "touches" : "DIFF";
    return c;
}

// The largest difference of a colour or alpha channel between two runs' values on the voxels
// both hold; infinity when they hold different channels, -1 without colour. Normals are not
// compared: a mean normal that rounding puts near the cancelled-normal line (opposite faces in
// one voxel: attributes/surface_values.h) is zero in one run and a unit vector in the other.
double maxColourDifference(const hyvox::VoxelizeResult& a, const hyvox::VoxelizeResult& b) {
    const int n = a.attributes.channels();
    if (n != b.attributes.channels() || a.attributes.color != b.attributes.color) return HUGE_VAL;
    if (!a.attributes.color) return -1;
    const int colour_channels = a.attributes.normalOffset();  // colour, then alpha if any
    auto key = [](const std::array<std::int32_t, 3>& p) {
        return (std::uint64_t(p[0]) << 42) | (std::uint64_t(p[1]) << 21) | std::uint64_t(p[2]);
    };
    const auto coords_b = b.occupancy.coords();
    std::unordered_map<std::uint64_t, std::size_t> index_b(coords_b.size());
    for (std::size_t v = 0; v < coords_b.size(); ++v) index_b.emplace(key(coords_b[v]), v);
    const std::vector<float> values_a = hyvox::valuesInCoordsOrder(a.occupancy, a.attributes);
    const std::vector<float> values_b = hyvox::valuesInCoordsOrder(b.occupancy, b.attributes);
    const auto coords_a = a.occupancy.coords();
    double worst = 0;
    for (std::size_t v = 0; v < coords_a.size(); ++v) {
        const auto found = index_b.find(key(coords_a[v]));
        if (found == index_b.end()) continue;
        for (int ch = 0; ch < colour_channels; ++ch)
            worst = std::max(worst,
                             double(std::fabs(values_a[v * std::size_t(n) + std::size_t(ch)] -
                                              values_b[found->second * std::size_t(n) + std::size_t(ch)])));
    }
    return worst;
}

// Live rows for the scenes an artist edits live (the 871k dragon at most).
constexpr std::size_t kLiveMaxTriangles = 1000000;

// The GL methods' pieces are clipped in double like cpu's (the tests hold the means to 2e-5);
// a piece lost or counted twice moves a colour mean by more than this.
constexpr double kAttributeTolerance = 1e-3;

// An attribute row's binary time, the price of the attributes (wall ratio) and the value
// difference, for the log line ("" elsewhere).
std::string attributeText(const Checked& c, double wall_ms) {
    if (c.binary_wall_ms <= 0) return "";
    char buf[96];
    std::snprintf(buf, sizeof buf, " binary wall %.2f (x%.2f) max diff %.2g", c.binary_wall_ms,
                  wall_ms / c.binary_wall_ms, c.attr_max_diff);
    return buf;
}

// GL_RENDERER and friends of the GL worker's context, after the EGL devices it chose from;
// `hardware` says whether that context is on a hardware device.
std::string deviceInfo(const std::string& selection, bool& hardware) {
    hardware = false;
    std::string info;
    for (const hyvox::GlDevice& d : hyvox::listGlDevices())
        info += "egl_device=" + std::to_string(d.index) + " " + d.name + (d.software ? " (software)" : " (hardware)") +
            "\n";
    try {
        hyvox::gl::GlWorker& worker = hyvox::gl::GlWorker::get(selection);
        hardware = !worker.device().software;
        info += worker.run([&] {
            const auto text = [](GLenum name) {
                const auto* s = reinterpret_cast<const char*>(glGetString(name));
                return std::string(s ? s : "?");
            };
            GLint tess = 0, ssbo = 0;
            glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &tess);
            glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssbo);
            return "gl_device_used=" + std::to_string(worker.device().index) + " " + worker.device().name +
                (worker.device().software ? " (software)" : " (hardware)") + "\nGL_VENDOR=" + text(GL_VENDOR) +
                "\nGL_RENDERER=" + text(GL_RENDERER) + "\nGL_VERSION=" + text(GL_VERSION) +
                "\nGL_SHADING_LANGUAGE_VERSION=" + text(GL_SHADING_LANGUAGE_VERSION) +
                "\nGL_MAX_TESS_GEN_LEVEL=" + std::to_string(tess) +
                "\nGL_MAX_SHADER_STORAGE_BLOCK_SIZE=" + std::to_string(ssbo) + "\n";
        });
    } catch (const std::exception& e) {
        info += "gl_error=" + field(e.what()) + "\n";
    }
    return info;
}

const char* kHeader =
    "step,scene,triangles,mode,res,method,threads,runs,gpu_ms,pass0_ms,pass1_ms,pass2_ms,stage_ms,wall_ms,first_ms,"
    "cutoff,large_triangles,cutoff_search_runs,tiles,voxels,ref_voxels,check,missed,false_voxels,touches,unexplained,"
    "bias,bias_thin,points,elapsed_s,stages,binary_wall_ms,attr_max_diff\n";

// One step ("thin@256", or "threads@512": cpu alone at 1, 2, 4, ... threads) on one scene.
class Bench {
public:
    Bench(std::FILE* csv, const hyvox::VoxelizeOptions& base, int repeat, double row_budget_s)
        : csv_(csv), base_(base), repeat_(repeat), row_budget_ms_(row_budget_s * 1000) {}

    int failures() const { return failures_; }
    double elapsedS() const { return clock_.elapsedMs() / 1000.0; }

    // cpu (the oracle), then hybrid, triangle and fragment checked against it, then (once per
    // scene and resolution) tessellation with its bias.
    void exactStep(std::size_t step, const std::string& spec, const hyvox::Mesh& mesh, hyvox::Mode mode, int res) {
        hyvox::VoxelizeOptions o = options(res);
        o.mode = mode;
        o.method = hyvox::Method::Cpu;
        const Row cpu = timeMethod(mesh, o, repeat_, row_budget_ms_);
        emit(step, spec, mesh, hyvox::toString(mode), res, "cpu", cpu, Checked{});
        if (!cpu.error.empty()) return;
        for (hyvox::Method method : {hyvox::Method::Hybrid, hyvox::Method::Triangle, hyvox::Method::Fragment}) {
            o.method = method;
            const Row row = timeMethod(mesh, o, repeat_, row_budget_ms_);
            const Checked c = row.error.empty() ? againstCpu(mesh, mode, row.last, cpu.last) : Checked{};
            emit(step, spec, mesh, hyvox::toString(mode), res, hyvox::toString(method), row, c);
        }
        if (!tessellated_.insert(spec + "@" + std::to_string(res)).second) return;
        o.method = hyvox::Method::Tessellation;
        const Row row = timeMethod(mesh, o, repeat_, row_budget_ms_);
        Checked c;
        if (row.error.empty()) {
            // Both exact sets: the step's own (cpu) and the other mode's, made here.
            hyvox::VoxelizeOptions other = o;
            other.method = hyvox::Method::Cpu;
            other.mode = mode == hyvox::Mode::Thin ? hyvox::Mode::Conservative : hyvox::Mode::Thin;
            const hyvox::VoxelizeResult second = hyvox::voxelize(mesh.view(), other);
            const hyvox::VoxelizeResult& conservative = mode == hyvox::Mode::Conservative ? cpu.last : second;
            const hyvox::VoxelizeResult& thin = mode == hyvox::Mode::Thin ? cpu.last : second;
            const hyvox::AccuracyReport acc = compareToReference(row.last.occupancy, conservative.occupancy);
            c.check = "bias";
            c.ref_voxels = acc.reference_voxels;
            c.missed = acc.missed_voxels;
            c.false_voxels = acc.false_voxels;
            c.bias = acc.bias;
            c.bias_thin = compareToReference(row.last.occupancy, thin.occupancy).bias;
        }
        // Tessellation has no mode: its row sits in the step's (bias is against conservative).
        emit(step, spec, mesh, hyvox::toString(mode), res, "tessellation", row, c);
    }

    // Each exact method's binary run, then its attribute run (colour where the scene has
    // colours, and normals; conservative), the latter's voxels and values against cpu's.
    void attributeStep(std::size_t step, const std::string& spec, const hyvox::Mesh& mesh, int res) {
        hyvox::VoxelizeOptions o = options(res);
        o.mode = hyvox::Mode::Conservative;
        const hyvox::AttributeSet attributes = hyvox::parseAttributeSet(mesh.view().colors ? "color,normal" : "normal");
        Row cpu;
        for (hyvox::Method method :
             {hyvox::Method::Cpu, hyvox::Method::Hybrid, hyvox::Method::Triangle, hyvox::Method::Fragment}) {
            o.method = method;
            o.attributes = {};
            const Row binary = timeMethod(mesh, o, repeat_, row_budget_ms_);
            o.attributes = attributes;
            Row row = timeMethod(mesh, o, repeat_, row_budget_ms_);
            Checked c;
            if (method != hyvox::Method::Cpu && row.error.empty() && cpu.error.empty()) {
                c = againstCpu(mesh, o.mode, row.last, cpu.last);
                c.attr_max_diff = maxColourDifference(row.last, cpu.last);
                if (c.attr_max_diff > kAttributeTolerance) c.check = "DIFF";
            }
            c.binary_wall_ms = binary.error.empty() ? binary.wall_ms : -1;
            emit(step, spec, mesh, "attributes", res, hyvox::toString(method), row, c);
            if (method == hyvox::Method::Cpu) {
                if (!row.error.empty()) return;
                cpu = std::move(row);
            }
        }
    }

    // The cpu method (conservative) at 1, 2, 4, ... threads up to the machine's, then all
    // (threads 0), each checked against the all-threads voxels.
    void threadsStep(std::size_t step, const std::string& spec, const hyvox::Mesh& mesh, int res) {
        hyvox::VoxelizeOptions o = options(res);
        o.method = hyvox::Method::Cpu;
        o.threads = 0;
        const Row all = timeMethod(mesh, o, repeat_, row_budget_ms_);
        emit(step, spec, mesh, hyvox::toString(o.mode), res, "cpu", all, Checked{});
        if (!all.error.empty()) return;
        const int cores = int(std::thread::hardware_concurrency());
        for (int threads = 1; threads <= cores; threads *= 2) {
            o.threads = threads;
            const Row row = timeMethod(mesh, o, repeat_, row_budget_ms_);
            Checked c;
            c.ref_voxels = all.last.stats.voxel_count;
            if (row.error.empty()) c.check = row.last.occupancy == all.last.occupancy ? "equal" : "DIFF";
            emit(step, spec, mesh, hyvox::toString(o.mode), res, "cpu", row, c);
        }
    }

    // Live's updates as its worker runs them (core/live_run.py), Blender's part aside: each
    // update moves another vertex by a tenth of a voxel (a new state every time), puts the
    // grid on the lattice fixed in world space (the voxel size of the first evaluation, the
    // origin the whole multiple of it at or below the bounds: snap_origin) and voxelizes
    // and writes the .vdb. Per mode (surface and solid, the add-on's default) cpu, then hybrid
    // checked against cpu on the last state. wall_ms: the median update (voxelize + write);
    // updates a second = 1000 / wall_ms; stage_ms: its voxelize part.
    void liveStep(std::size_t step, const std::string& spec, const hyvox::Mesh& mesh, int res) {
        if (mesh.triangleCount() > kLiveMaxTriangles) {  // the subdivided dragons: minutes of solid cpu
            std::printf("# live: %s skipped (over %zu triangles)\n", sceneName(spec).c_str(), kLiveMaxTriangles);
            return;
        }
        const hyvox::Bounds bounds = hyvox::validate(mesh.view()).bounds;
        double longest = 0;
        for (int a = 0; a < 3; ++a) longest = std::max(longest, bounds.max[a] - bounds.min[a]);
        const double voxel_size = longest / res;
        const std::string path = (std::filesystem::temp_directory_path() / "hyvox_bench_live.vdb").string();
        for (hyvox::Mode mode : {hyvox::Mode::Conservative, hyvox::Mode::Solid}) {
            for (hyvox::Method method : {hyvox::Method::Cpu, hyvox::Method::Hybrid}) {
                hyvox::Mesh edited = mesh;
                hyvox::VoxelizeOptions o = options(res);
                o.mode = mode;
                o.method = method;
                o.grid.voxel_size = voxel_size;
                o.grid.snap_origin = true;
                Row row;
                std::vector<double> update, voxelize, write;
                try {
                    for (int edit = 0; edit <= repeat_ * 4; ++edit) {  // edit 0: the warm-up
                        hyvox::Stopwatch watch;
                        edited.positions[3 * ((std::size_t(edit) * 7919) % edited.vertexCount()) + 2] +=
                            float(0.1 * voxel_size);
                        row.last = hyvox::voxelize(edited.view(), o);
                        const double voxelized = watch.elapsedMs();
                        hyvox::writeVdb(row.last, path);
                        if (edit == 0) {
                            row.first_ms = watch.elapsedMs();
                            continue;
                        }
                        update.push_back(watch.elapsedMs());
                        voxelize.push_back(voxelized);
                        write.push_back(update.back() - voxelized);
                        if (median(update) * double(update.size()) > row_budget_ms_ * 2) break;
                    }
                    row.runs = int(update.size());
                    row.wall_ms = median(update);
                    row.stage_ms = median(voxelize);
                    double p0, p1, p2;
                    row.gpu_ms = gpuPasses(row.last.stats, p0, p1, p2);  // of the last update
                    row.pass2_ms = median(write);                        // the write, in the CSV's pass2 column
                } catch (const std::exception& e) {
                    row.error = e.what();
                }
                Checked c;
                if (method != hyvox::Method::Cpu && row.error.empty()) {
                    o.method = hyvox::Method::Cpu;  // the oracle: cpu on the same last state and lattice
                    c = againstCpu(edited, mode, row.last, hyvox::voxelize(edited.view(), o));
                }
                const std::string label = std::string("live-") + hyvox::toString(mode);
                emit(step, spec, mesh, label.c_str(), res, hyvox::toString(method), row, c);
                if (row.error.empty() && row.wall_ms > 0)
                    std::printf("# live %s %s@%d %s: %.1f updates a second (voxelize %.2f + write %.2f ms)\n",
                                sceneName(spec).c_str(), hyvox::toString(mode), res, hyvox::toString(method),
                                1000.0 / row.wall_ms, row.stage_ms, row.pass2_ms);
            }
        }
        std::error_code ignored;
        std::filesystem::remove(path, ignored);
    }

private:
    hyvox::VoxelizeOptions options(int res) const {
        hyvox::VoxelizeOptions o = base_;
        o.grid.resolution = res;
        o.tessellation.counts = false;  // binary voxelization, as the papers time it
        return o;
    }

    void emit(std::size_t step, const std::string& spec, const hyvox::Mesh& mesh, const char* mode, int res,
              const char* method, const Row& row, const Checked& c) {
        const hyvox::Stats& s = row.last.stats;
        const hyvox::HybridStats h = s.hybrid.value_or(hyvox::HybridStats{});
        const std::string check = row.error.empty() ? c.check : "ERROR " + field(row.error);
        const std::string name = sceneName(spec);
        std::fprintf(csv_,
                     "%zu,%s,%zu,%s,%d,%s,%d,%d,%.4f,%.4f,%.4f,%.4f,%.3f,%.3f,%.3f,%.3f,%llu,%llu,%llu,%llu,%llu,%s,"
                     "%llu,%llu,%llu,%llu,%.6f,%.6f,%llu,%.1f,%s,%.3f,%.3g\n",
                     step, name.c_str(), mesh.triangleCount(), mode, res, method, row.threads, row.runs, row.gpu_ms,
                     row.pass0_ms, row.pass1_ms, row.pass2_ms, row.stage_ms, row.wall_ms, row.first_ms,
                     s.hybrid ? h.cutoff : 0.0, (unsigned long long)h.large_triangles,
                     (unsigned long long)h.cutoff_search_runs, (unsigned long long)s.tiles,
                     (unsigned long long)s.voxel_count, (unsigned long long)c.ref_voxels, check.c_str(),
                     (unsigned long long)c.missed, (unsigned long long)c.false_voxels, (unsigned long long)c.touches,
                     (unsigned long long)c.unexplained, c.bias, c.bias_thin,
                     (unsigned long long)(s.tessellation ? s.tessellation->points : 0), elapsedS(),
                     stageText(s).c_str(), c.binary_wall_ms, c.attr_max_diff);
        std::fflush(csv_);
        std::printf(
            "%-26s %9zu %-12s %4d %-12s t%-2d runs %d gpu %9.3f (p0 %.3f p1 %.3f p2 %.3f) stage %9.2f wall "
            "%9.2f first %9.2f voxels %llu %s%s\n",
            name.c_str(), mesh.triangleCount(), mode, res, method, row.threads, row.runs, row.gpu_ms, row.pass0_ms,
            row.pass1_ms, row.pass2_ms, row.stage_ms, row.wall_ms, row.first_ms, (unsigned long long)s.voxel_count,
            check.c_str(), attributeText(c, row.wall_ms).c_str());
        std::fflush(stdout);
        if (!row.error.empty() || c.check == "DIFF" || (c.check == "bias" && c.false_voxels)) ++failures_;
    }

    std::FILE* csv_;
    hyvox::VoxelizeOptions base_;
    int repeat_;
    double row_budget_ms_;
    hyvox::Stopwatch clock_;
    std::set<std::string> tessellated_;  // "scene@res" done
    int failures_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    std::string mesh_dir = ".", csv_path, info_path;
    std::vector<std::string> order = {"thin@256", "thin@512", "thin@128", "conservative@256", "thin@1024"};
    std::vector<std::string> scenes = {"bunny_stanford_69k.ply",           "dragon_stanford_res2_203k.ply.gz",
                                       "sponza_crytek_262k_vcolor.ply.gz", "triangle",
                                       "dragon_stanford_871k.ply.gz",      "dragon_stanford_871k.ply.gz:x4",
                                       "dragon_stanford_871k.ply.gz:x16"};
    int repeat = 5;
    double row_budget_s = 3, budget_s = 300;
    bool require_hardware = false;
    hyvox::VoxelizeOptions base;
    base.hybrid.cutoff = -1.0;            // auto
    hyvox::bench::readEnvironment(base);  // HYVOX_GL_DEVICE, HYVOX_GL_WALL_TIMING, ...
    for (int a = 1; a < argc; ++a) {
        const std::string arg = argv[a];
        auto next = [&] { return hyvox::bench::optionValue(argc, argv, a); };
        if (arg == "--mesh-dir")
            mesh_dir = next();
        else if (arg == "--csv")
            csv_path = next();
        else if (arg == "--info")
            info_path = next();
        else if (arg == "--order")
            order = splitList(next());
        else if (arg == "--scenes")
            scenes = splitList(next());
        else if (arg == "--repeat")
            repeat = std::max(1, std::atoi(next().c_str()));
        else if (arg == "--row-budget-s")
            row_budget_s = std::atof(next().c_str());
        else if (arg == "--budget-s")
            budget_s = std::atof(next().c_str());
        else if (arg == "--device")
            base.gl.device = next();
        else if (arg == "--require-hardware")
            require_hardware = true;
        else {
            std::fprintf(stderr,
                         "usage: bench_device --mesh-dir DIR --csv FILE [--info FILE] [--order STEP,...] "
                         "[--scenes S,...] [--repeat N] [--row-budget-s S] [--budget-s S] [--device D] "
                         "[--require-hardware]\n"
                         "  STEP: MODE@RES (thin@256), threads@RES (cpu alone at 1, 2, 4, ... threads) or\n"
                         "        attributes@RES (each exact method binary, then with colour and normals) or\n"
                         "        live@RES (Live's updates: an edit, voxelize, write, cpu and hybrid)\n");
            return 2;
        }
    }
    if (csv_path.empty()) {
        std::fprintf(stderr, "bench_device: --csv FILE is required\n");
        return 2;
    }
    std::vector<Step> steps;
    for (const std::string& s : order) steps.push_back(parseStep(s));

    bool hardware = false;
    const std::string info = deviceInfo(base.gl.device, hardware);
    std::printf("%s", info.c_str());
    std::fflush(stdout);
    if (!info_path.empty())
        if (std::FILE* f = std::fopen(info_path.c_str(), "w")) {
            std::fputs(info.c_str(), f);
            std::fclose(f);
        }
    if (require_hardware && !hardware) {  // on a lent GPU: stop before minutes of CPU-only work
        std::printf("# --require-hardware: no GL context on a hardware device (above); nothing run\n");
        return 3;
    }
    std::FILE* csv = std::fopen(csv_path.c_str(), "w");
    if (!csv) {
        std::fprintf(stderr, "bench_device: cannot write %s\n", csv_path.c_str());
        return 1;
    }
    std::fputs(kHeader, csv);
    std::fflush(csv);

    Bench bench(csv, base, repeat, row_budget_s);
    Scenes meshes(mesh_dir);
    int failures = 0;
    for (std::size_t si = 0; si < steps.size(); ++si) {
        const Step& step = steps[si];
        for (const std::string& spec : scenes) {
            if (bench.elapsedS() > budget_s) {
                std::printf("# budget of %.0f s reached at %.0f s: skipped %s (step %s) and everything after it\n",
                            budget_s, bench.elapsedS(), spec.c_str(), order[si].c_str());
                std::fclose(csv);
                return bench.failures() + failures ? 1 : 0;
            }
            if ((step.threads || step.live) && spec == "triangle") continue;  // nothing to spread or edit
            try {
                const hyvox::Mesh& mesh = meshes.get(spec);
                if (step.threads)
                    bench.threadsStep(si, spec, mesh, step.resolution);
                else if (step.attributes)
                    bench.attributeStep(si, spec, mesh, step.resolution);
                else if (step.live)
                    bench.liveStep(si, spec, mesh, step.resolution);
                else
                    bench.exactStep(si, spec, mesh, step.mode, step.resolution);
            } catch (const std::exception& e) {
                std::printf("# %s (step %s): %s\n", spec.c_str(), order[si].c_str(), e.what());
                ++failures;
            }
        }
    }
    std::fclose(csv);
    std::printf("# done in %.1f s, %d failure(s)\n", bench.elapsedS(), bench.failures() + failures);
    return bench.failures() + failures ? 1 : 0;
}
