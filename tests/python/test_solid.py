# SPDX-License-Identifier: GPL-3.0-or-later
"""Solid mode against independent oracles.

Closed meshes: every voxel outside the conservative surface is set exactly when OpenVDB's
level set (pyopenvdb createLevelSetFromPolygons, its own sign flood) is negative at its centre.
OpenVDB's sign is known to go wrong in cavities thinner than a voxel; where it disagrees with
us, a brute-force double-precision winding number must side with us, and such voxels must be
rare. Open and messy meshes: the inside voxels equal a brute-force double-precision winding
number >= 0.5 computed here in numpy, away from |w - 0.5| < 0.05. Also: count = surface +
inside, whole bricks are tiles in the OpenVDB tree, and the front doors take the options."""

import json
import subprocess

import numpy as np
import pytest

import hyvox
from shapes import icosphere

CLOSED_FILES = ["happy_buddha_100k.ply", "armadillo_52k.ply", "igea_cyberware_268k.ply.gz", "spot_vcolor.ply"]
OPEN_FILES = ["bunny_stanford_69k.ply", "shark_holes.ply", "elephant_holes.ply", "spider_messy.ply"]
# How each open file's winding numbers are sampled: from its open edges' sheets when they are
# few against its triangles (the bunny: 223 against 69k), else from the fast winding tree.
OPEN_FILE_SAMPLING = {"bunny_stanford_69k.ply": "sheets of the open edges"}
RESOLUTION = 64
SAMPLES = 800  # centres the brute force checks per mesh file (all of them for the small shapes)


# --- meshes made here -------------------------------------------------------------------

CUBE_FACES = np.array(
    [
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [2, 3, 7],
        [2, 7, 6],
        [1, 2, 6],
        [1, 6, 5],
        [0, 4, 7],
        [0, 7, 3],
    ],
    np.uint32,
)


def cube(lo=(0, 0, 0), hi=(1, 1, 1)):
    """A closed cube with outward-facing (counter-clockwise seen from outside) triangles."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    corners = [
        (x0, y0, z0),
        (x1, y0, z0),
        (x1, y1, z0),
        (x0, y1, z0),
        (x0, y0, z1),
        (x1, y0, z1),
        (x1, y1, z1),
        (x0, y1, z1),
    ]
    return np.array(corners, np.float32), CUBE_FACES.copy()


def join(*meshes):
    vertices, triangles, base = [], [], 0
    for v, t in meshes:
        vertices.append(v)
        triangles.append(t + base)
        base += len(v)
    return np.concatenate(vertices), np.concatenate(triangles).astype(np.uint32)


def messy_shapes():
    """name -> (mesh, what auto must report)."""
    open_cube = cube()
    open_cube = (open_cube[0], open_cube[1][2:])  # the bottom face removed
    flipped_face = cube()
    flipped_face[1][4:6] = flipped_face[1][4:6, ::-1]  # one side turned inside out
    return {
        "cube_without_a_face": (open_cube, "boundary"),
        "cube_with_a_flipped_face": (flipped_face, "misoriented"),
        # Two closed cubes that overlap: the overlap has winding number 2 (parity would leave it empty).
        "overlapping_cubes": (join(cube(), cube((0.4, 0.3, 0.2), (1.5, 1.2, 1.3))), "closed"),
        # Two cubes sharing one edge: used four times, twice each way (non-manifold, balanced).
        "cubes_sharing_an_edge": (join(cube(), cube((1, 1, 0), (2, 2, 1))), "balanced"),
        # A cube inside a cube whose faces are flipped: a hollow box (winding number 0 inside).
        "nested_cube_flipped": (
            join(cube((0, 0, 0), (2, 2, 2)), (cube((0.5, 0.6, 0.7), (1.5, 1.4, 1.3))[0], CUBE_FACES[:, ::-1].copy())),
            "closed",
        ),
    }


# --- oracles -----------------------------------------------------------------------------


def brute_force_winding(vertices, triangles, points):
    """Sum of the triangles' solid angles (van Oosterom & Strackee) over 4 pi, in float64."""
    a0 = vertices[triangles[:, 0]].astype(np.float64)
    b0 = vertices[triangles[:, 1]].astype(np.float64)
    c0 = vertices[triangles[:, 2]].astype(np.float64)
    out = np.empty(len(points))
    chunk = max(1, 4_000_000 // max(len(triangles), 1))
    for s in range(0, len(points), chunk):
        p = points[s : s + chunk, None, :]
        a, b, c = a0 - p, b0 - p, c0 - p
        la, lb, lc = (np.linalg.norm(x, axis=2) for x in (a, b, c))
        det = np.einsum("ijk,ijk->ij", a, np.cross(b, c))
        den = (
            la * lb * lc
            + np.einsum("ijk,ijk->ij", a, b) * lc
            + np.einsum("ijk,ijk->ij", b, c) * la
            + np.einsum("ijk,ijk->ij", c, a) * lb
        )
        out[s : s + chunk] = 2 * np.arctan2(det, den).sum(axis=1) / (4 * np.pi)
    return out


def centres(grid, ijk):
    return np.array(grid.origin) + (ijk + 0.5) * grid.voxel_size


def openvdb_negative(vertices, triangles, grid):
    """Whether OpenVDB's level set of the mesh is negative at each voxel centre of `grid`."""
    import pyopenvdb as vdb

    h = grid.voxel_size
    transform = vdb.createLinearTransform(voxelSize=h)
    transform.translate(tuple(np.array(grid.origin) + h / 2))
    level_set = vdb.FloatGrid.createLevelSetFromPolygons(
        vertices.astype(np.float32), triangles=triangles.astype(np.uint32), transform=transform, halfWidth=2.0
    )
    values = np.zeros(grid.dims, np.float32)
    level_set.copyToArray(values, ijk=(0, 0, 0))
    return values < 0


def solid_and_surface(vertices, triangles, resolution, **options):
    solid = hyvox.voxelize(vertices, triangles, resolution=resolution, mode="solid", **options)
    options.pop("inside", None)
    surface = hyvox.voxelize(vertices, triangles, resolution=resolution, mode="conservative", **options)
    return solid, surface


# --- closed meshes against OpenVDB ----------------------------------------------------------


def check_against_openvdb(vertices, triangles, **options):
    solid, surface = solid_and_surface(vertices, triangles, RESOLUTION, **options)
    dense, shell = solid.to_dense(), surface.to_dense()
    assert (dense | ~shell).all(), "the solid lost surface voxels"
    free = ~shell
    negative = openvdb_negative(vertices, triangles, solid)
    disagree = np.argwhere(free & (dense != negative))
    # Where OpenVDB's sign differs, the exact winding number must side with us, clearly.
    if len(disagree):
        w = brute_force_winding(vertices, triangles, centres(solid, disagree))
        ours = dense[tuple(disagree.T)]
        assert ((w >= 0.5) == ours).all() and (np.abs(w - 0.5) > 0.4).all(), (disagree, w)
    assert len(disagree) <= 1e-4 * free.sum() + 20
    return solid


@pytest.mark.parametrize("inside", ["parity", "winding"])
@pytest.mark.parametrize("name", CLOSED_FILES)
def test_closed_mesh_files_match_openvdb(mesh_dir, name, inside):
    vertices, triangles = hyvox.read_mesh(mesh_dir / name)
    solid = check_against_openvdb(vertices, triangles, inside=inside)
    assert solid.stats["solid"]["inside_rule"] == inside


@pytest.mark.parametrize("inside", ["parity", "winding", "auto"])
@pytest.mark.parametrize("shape", ["cube", "sphere"])
def test_closed_shapes_match_openvdb(shape, inside):
    vertices, triangles = cube((0.1, 0.2, 0.3), (1.3, 1.1, 0.9)) if shape == "cube" else icosphere(3)
    solid = check_against_openvdb(vertices, triangles, inside=inside)
    stats = solid.stats["solid"]
    assert stats["boundary_edges"] == stats["nonmanifold_edges"] == stats["misoriented_edges"] == 0
    if inside == "auto":
        assert stats["evaluation"] == "ray crossings" and "closed" in stats["reason"]


@pytest.mark.parametrize("inside", ["parity", "winding"])
def test_a_gl_method_fills_like_openvdb(mesh_dir, inside):
    vertices, triangles = hyvox.read_mesh(mesh_dir / "armadillo_52k.ply")
    solid = check_against_openvdb(vertices, triangles, inside=inside, method="hybrid", gl_device="software")
    cpu = hyvox.voxelize(vertices, triangles, resolution=RESOLUTION, mode="solid", inside=inside)
    assert np.array_equal(np.sort(solid.coords(), axis=0), np.sort(cpu.coords(), axis=0))


# --- open and messy meshes against the brute-force winding number ---------------------------


def check_against_brute_force(vertices, triangles, resolution, samples=None, seed=0):
    solid, surface = solid_and_surface(vertices, triangles, resolution, inside="winding")
    dense, shell = solid.to_dense(), surface.to_dense()
    free = np.argwhere(~shell)
    if samples is not None and len(free) > samples:
        free = free[np.random.default_rng(seed).choice(len(free), samples, replace=False)]
    w = brute_force_winding(vertices, triangles, centres(solid, free))
    clear = np.abs(w - 0.5) >= 0.05
    assert clear.mean() > 0.9
    got = dense[tuple(free.T)]
    wrong = clear & (got != (w >= 0.5))
    assert not wrong.any(), (free[wrong], w[wrong])
    return solid, free, w


@pytest.mark.parametrize("name", OPEN_FILES)
def test_open_mesh_files_match_brute_force_winding(mesh_dir, name):
    vertices, triangles = hyvox.read_mesh(mesh_dir / name)
    _, _, w = check_against_brute_force(vertices, triangles, 48, samples=SAMPLES, seed=len(name))
    assert (w >= 0.55).any() and (w <= 0.45).any()  # the sample sees inside and outside
    auto = hyvox.voxelize(vertices, triangles, resolution=48, mode="solid").stats["solid"]
    assert auto["inside_rule"] == "winding"
    assert auto["evaluation"] == OPEN_FILE_SAMPLING.get(name, "fast winding numbers")
    assert auto["reason"].startswith("auto: not closed") and auto["boundary_edges"] > 0


@pytest.mark.parametrize("name", list(messy_shapes()))
def test_messy_shapes_match_brute_force_winding(name):
    (vertices, triangles), finding = messy_shapes()[name]
    solid, free, w = check_against_brute_force(vertices, triangles, 64)
    auto = hyvox.voxelize(vertices, triangles, resolution=64, mode="solid")
    stats = auto.stats["solid"]
    assert stats["inside_rule"] == "winding"
    if finding == "closed":
        assert stats["evaluation"] == "ray crossings" and "closed and consistently oriented" in stats["reason"]
    elif finding == "balanced":
        assert stats["evaluation"] == "ray crossings" and "as often each way" in stats["reason"]
        assert stats["nonmanifold_edges"] > 0 and stats["boundary_edges"] == stats["misoriented_edges"] == 0
    else:
        assert stats["evaluation"] == "fast winding numbers" and stats[finding + "_edges"] > 0
        assert finding in stats["reason"]
    # auto and winding agree away from the threshold (same answer, other evaluation).
    clear = np.abs(w - 0.5) >= 0.05
    assert np.array_equal(auto.to_dense()[tuple(free[clear].T)], solid.to_dense()[tuple(free[clear].T)])


def atrium(leaves=300, seed=7):
    """A Sponza-like open mesh: a room without a roof whose floor and walls are a few large
    triangles, a thick gallery slab with one side left open, and many small open quads
    (leaves) floating in and around it, each with four boundary edges."""
    room_v, room_t = cube((0, 0, 0), (4, 3, 2))
    room_t = room_t[np.any(room_v[room_t][:, :, 2] < 2, axis=1)]  # the top face removed
    slab_v, slab_t = cube((0.2, 0.2, 0.9), (2.5, 2.8, 1.1))
    slab_t = slab_t[~np.all(slab_v[slab_t][:, :, 0] == 2.5, axis=1)]  # its +x side removed
    rng = np.random.default_rng(seed)
    centres_ = rng.uniform((-1, -1, 0.2), (5, 4, 2.8), (leaves, 3))
    u = rng.normal(size=(leaves, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    w = np.cross(u, rng.normal(size=(leaves, 3)))
    w /= np.linalg.norm(w, axis=1, keepdims=True)
    size = rng.uniform(0.03, 0.15, (leaves, 1))
    quad_v = np.concatenate(
        [centres_ + size * (sa * u + sb * w) for sa, sb in [(-1, -1), (1, -1), (1, 1), (-1, 1)]], axis=1
    )
    quad_v = quad_v.reshape(-1, 3)
    base = 4 * np.arange(leaves)[:, None]
    quad_t = np.concatenate([base + [0, 1, 2], base + [0, 2, 3]])
    return join((room_v, room_t), (slab_v, slab_t), (quad_v.astype(np.float32), quad_t.astype(np.uint32)))


def test_open_mesh_with_large_triangles_and_many_open_edges_matches_brute_force_winding():
    # The case open meshes are decided by brick by brick from the smooth part of the winding
    # number (w minus ray crossings, plus the open edges' sheets), interpolated: every voxel
    # outside the surface is checked.
    vertices, triangles = atrium()
    solid, free, w = check_against_brute_force(vertices, triangles, 64)
    assert (w >= 0.55).sum() > 1000 and (w <= 0.45).sum() > 1000
    stats = solid.stats["solid"]
    assert stats["boundary_edges"] > 1000 and stats["evaluation"] == "fast winding numbers"
    assert stats["interpolated_voxels"] > len(free) / 2  # the interpolation decided most of them


def test_sponza_matches_brute_force_winding(mesh_dir):
    vertices, triangles = hyvox.read_mesh(mesh_dir / "sponza_crytek_262k_vcolor.ply.gz")
    solid, _, w = check_against_brute_force(vertices, triangles, 64, samples=300, seed=11)
    assert (w >= 0.55).any() and (w <= 0.45).any()
    assert solid.stats["solid"]["interpolated_voxels"] > 0


def test_overlap_is_filled_and_the_hollow_stays_empty():
    shapes = messy_shapes()
    overlap = hyvox.voxelize(*shapes["overlapping_cubes"][0], resolution=64, mode="solid")
    parity = hyvox.voxelize(*shapes["overlapping_cubes"][0], resolution=64, mode="solid", inside="parity")
    i, j, k = (np.floor((np.array([0.7, 0.65, 0.6]) - overlap.origin) / overlap.voxel_size)).astype(int)
    assert overlap.to_dense()[i, j, k] and not parity.to_dense()[i, j, k]
    hollow = hyvox.voxelize(*shapes["nested_cube_flipped"][0], resolution=64, mode="solid")
    i, j, k = (np.floor((np.array([1.0, 1.0, 1.0]) - hollow.origin) / hollow.voxel_size)).astype(int)
    assert not hollow.to_dense()[i, j, k]


# --- counts, tiles, front doors -----------------------------------------------------------


def test_count_is_surface_plus_inside_and_interiors_are_tiles(tmp_path):
    import pyopenvdb as vdb

    vertices, triangles = icosphere(3)
    solid, surface = solid_and_surface(vertices, triangles, 96)
    stats = solid.stats
    assert solid.voxel_count == surface.voxel_count + stats["solid"]["inside_voxels"]
    ijk = solid.coords()
    assert len(ijk) == solid.voxel_count and len(np.unique(ijk, axis=0)) == len(ijk)
    dense = solid.to_dense()
    assert dense.sum() == solid.voxel_count and dense[tuple(ijk.T)].all()
    # The bricks that hold any voxel, and those wholly set: the latter are tiles, not leaves.
    bricks, per_brick = np.unique(ijk // 8, axis=0, return_counts=True)
    whole = int((per_brick == 512).sum())
    assert whole > 100 and stats["solid"]["tile_bricks"] == whole
    assert stats["leaves"] == len(bricks) - whole
    path = tmp_path / "sphere.vdb"
    solid.write_vdb(path)
    grid = vdb.read(str(path), "density")
    assert grid.activeVoxelCount() == solid.voxel_count
    assert grid.leafCount() == stats["leaves"]


def test_cli_takes_the_solid_options(cli, tmp_path):
    vertices, triangles = cube()
    mesh = tmp_path / "cube.obj"
    mesh.write_text(
        "".join(f"v {x} {y} {z}\n" for x, y, z in vertices)
        + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in triangles)
    )
    stats_path = tmp_path / "stats.json"
    subprocess.run(
        [
            str(cli),
            "voxelize",
            str(mesh),
            "-o",
            str(tmp_path / "cube.vdb"),
            "--resolution",
            "32",
            "--mode",
            "solid",
            "--inside",
            "winding",
            "--winding-beta",
            "3",
            "--stats-json",
            str(stats_path),
            "-q",
        ],
        check=True,
    )
    stats = json.loads(stats_path.read_text())
    assert stats["mode"] == "solid" and stats["voxel_count"] == 32**3
    assert stats["solid"]["inside_rule"] == "winding" and stats["options"]["winding_beta"] == 3
    bad = subprocess.run(
        [str(cli), "voxelize", str(mesh), "-o", str(tmp_path / "x.vdb"), "--inside", "sometimes"],
        capture_output=True,
        text=True,
    )
    assert bad.returncode != 0 and "parity, winding" in bad.stderr


def test_tiled_and_tessellation_runs_fill_the_same_inside(bunny):
    vertices, triangles = bunny
    whole = hyvox.voxelize(vertices, triangles, resolution=48, mode="solid")
    tiled = hyvox.voxelize(vertices, triangles, resolution=48, mode="solid", tile_size=16)
    assert tiled.stats["tiles"] > 1
    assert np.array_equal(np.sort(whole.coords(), axis=0), np.sort(tiled.coords(), axis=0))
    # The tessellation's surface is approximate; its inside is decided against the exact one,
    # so solid = its own surface + the same inside voxels as cpu's.
    tess = hyvox.voxelize(vertices, triangles, resolution=48, mode="solid", method="tessellation", gl_device="software")
    tess_surface = hyvox.voxelize(vertices, triangles, resolution=48, method="tessellation", gl_device="software")
    cpu_surface = hyvox.voxelize(vertices, triangles, resolution=48).to_dense()
    expected = tess_surface.to_dense() | (whole.to_dense() & ~cpu_surface)
    assert np.array_equal(tess.to_dense(), expected)
    # Tiled, with PN triangles (points reach past their triangle's box): the barrier's cpu
    # pass bins the triangles for itself.
    tess_tiled = hyvox.voxelize(
        vertices,
        triangles,
        resolution=48,
        mode="solid",
        method="tessellation",
        gl_device="software",
        tile_size=16,
        pn_triangles=True,
    )
    tess_tiled_surface = hyvox.voxelize(
        vertices, triangles, resolution=48, method="tessellation", gl_device="software", pn_triangles=True
    )
    assert tess_tiled.stats["tiles"] > 1
    assert np.array_equal(tess_tiled.to_dense(), tess_tiled_surface.to_dense() | (whole.to_dense() & ~cpu_surface))


def numpy_edge_closure(vertices, triangles):
    """The edge check's counts computed here: vertices welded on their exact position (-0 as +0),
    each edge's uses one way and the other."""
    _, weld = np.unique(vertices + np.float32(0.0), axis=0, return_inverse=True)
    welded = weld.reshape(-1)[triangles]
    uses = {}
    for a, b in np.concatenate([welded[:, [0, 1]], welded[:, [1, 2]], welded[:, [2, 0]]]):
        if a != b:
            forward = uses.setdefault((min(a, b), max(a, b)), [0, 0])
            forward[0 if a < b else 1] += 1
    counts = {"boundary_edges": 0, "nonmanifold_edges": 0, "misoriented_edges": 0}
    for forward, backward in uses.values():
        if forward + backward == 1:
            counts["boundary_edges"] += 1
        elif forward + backward > 2:
            counts["nonmanifold_edges"] += 1
        elif forward != backward:
            counts["misoriented_edges"] += 1
    return counts


def test_the_edge_check_welds_vertices_at_one_position():
    # A sphere as a soup (each triangle its own corners, some zeros negative), then with one
    # corner moved by a float's last bit and one triangle doubled: the counts equal numpy's.
    vertices, triangles = icosphere(2)
    soup = vertices[triangles.reshape(-1)].copy()
    soup[np.abs(soup) < 1e-7] = 0.0
    soup[::5][soup[::5] == 0.0] = -0.0
    soup_triangles = np.arange(len(soup), dtype=np.uint32).reshape(-1, 3)
    nudged = soup.copy()
    nudged[7, 0] = np.nextafter(nudged[7, 0], np.float32(np.inf))
    doubled = np.concatenate([soup_triangles, soup_triangles[:1]])
    for v, t in ((soup, soup_triangles), (nudged, soup_triangles), (soup, doubled)):
        stats = hyvox.voxelize(v, t, resolution=16, mode="solid", method="cpu").stats["solid"]
        expected = numpy_edge_closure(v, t)
        assert {key: stats[key] for key in expected} == expected
    assert numpy_edge_closure(soup, soup_triangles) == {
        "boundary_edges": 0,
        "nonmanifold_edges": 0,
        "misoriented_edges": 0,
    }
    assert numpy_edge_closure(nudged, soup_triangles)["boundary_edges"] > 0
