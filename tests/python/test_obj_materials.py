# SPDX-License-Identifier: GPL-3.0-or-later
# Colour from an OBJ's materials (mtllib/usemtl, MTL Kd and map_Kd): read_mesh, voxelize and
# the CLI give the colours of the same mesh passed as arrays, and the numpy oracle's; what the
# reader cannot use (a missing image or .mtl) is a warning and the material's Kd (or grey).

import numpy as np
import pytest
import pyopenvdb as vdb
from PIL import Image

import hyvox
from attribute_oracle import srgb_to_linear, voxel_attributes

# Part A: a tilted quad with UVs over the whole image (material "painted", textured).
# Part B: a triangle far from it (material "plain", Kd only), so no voxel mixes the two.
QUAD = np.array([[0, 0, 0.3], [4, 0, 0.7], [4, 4, 0.7], [0, 4, 0.3]], dtype=np.float32)
QUAD_UV = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float32)
TRIANGLE = np.array([[7, 0, 2], [9, 1, 2.5], [7, 3, 3]], dtype=np.float32)
PAINTED_KD = [0.2, 0.9, 0.1]  # replaced by the image (as Blender's importer does)
PLAIN_KD = [0.75, 0.25, 0.5]
RESOLUTION = 24


def pixels():
    rng = np.random.default_rng(12)
    return rng.integers(0, 256, size=(4, 5, 3), dtype=np.uint8)


def write_obj(folder, image="painted.png", mtl="scene.mtl", write_mtl=True, write_image=True):
    """The OBJ, its MTL and PNG in `folder`; returns the OBJ's path."""
    lines = [f"mtllib {mtl}"]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in QUAD.astype(float)]
    lines += [f"v {x!r} {y!r} {z!r}" for x, y, z in TRIANGLE.astype(float)]
    lines += [f"vt {u!r} {v!r}" for u, v in QUAD_UV.astype(float)] + ["vt 0 0"]
    lines += ["usemtl painted", "f 1/1 2/2 3/3 4/4", "usemtl plain", "f 5/5 6/5 7/5"]
    (folder / "scene.obj").write_text("\n".join(lines) + "\n")
    if write_mtl:
        (folder / mtl).write_text(
            "# two materials\nnewmtl painted\nKd {} {} {}\nmap_Kd {}\n\nnewmtl plain\nKa 0 0 0\nKd {} {} {}\n".format(
                *PAINTED_KD, image, *PLAIN_KD
            )
        )
    if write_image:
        Image.fromarray(pixels()).save(folder / "painted.png")
    return folder / "scene.obj"


def arrays():
    """The same mesh as arrays, in the order the OBJ reader numbers vertices and fans faces."""
    vertices = np.concatenate([QUAD, TRIANGLE])
    triangles = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6]], dtype=np.uint32)
    uvs = np.concatenate([QUAD_UV, np.zeros((3, 2), np.float32)])
    return vertices, triangles, uvs, np.array([0, 0, 1]), np.array([PAINTED_KD, PLAIN_KD], dtype=np.float32)


def voxelize_as_read(v, t, attrs):
    """voxelize() in colour with all that read_mesh(attributes=True) gave of the file's
    materials, as an artist's script would pass them on."""
    return hyvox.voxelize(
        v,
        t,
        resolution=RESOLUTION,
        attributes="color",
        uvs=attrs["uvs"],
        material_ids=attrs["material_ids"],
        palette=attrs["palette"],
        textures=attrs["textures"],
    )


def voxelize_arrays(textures, resolution=RESOLUTION, with_uvs=True, **options):
    """voxelize() in colour of arrays() (the OBJ's mesh and materials as arrays) with
    `textures`: the tests vary only the textures, the resolution, whether the UVs are
    passed, and the method."""
    vertices, triangles, uvs, material_ids, palette = arrays()
    if with_uvs:
        options["uvs"] = uvs
    return hyvox.voxelize(
        vertices,
        triangles,
        resolution=resolution,
        attributes="color",
        material_ids=material_ids,
        palette=palette,
        textures=textures,
        **options,
    )


def by_key(ijk, dims):
    ijk = np.asarray(ijk, dtype=np.int64)
    return (ijk[:, 0] * dims[1] + ijk[:, 1]) * dims[2] + ijk[:, 2]


def test_read_mesh_gives_the_materials(tmp_path):
    path = write_obj(tmp_path)
    v, t, attrs = hyvox.read_mesh(path, attributes=True)
    vertices, triangles, uvs, material_ids, palette = arrays()
    assert np.array_equal(v, vertices) and np.array_equal(t, triangles)
    np.testing.assert_array_equal(attrs["uvs"], uvs)
    np.testing.assert_array_equal(attrs["material_ids"], material_ids)
    np.testing.assert_array_equal(attrs["palette"], palette)
    assert attrs["material_names"] == ["painted", "plain"]
    assert attrs["textures"] == [str(tmp_path / "painted.png"), None]


def test_file_colours_equal_the_arrays_and_the_oracle(tmp_path, cli_voxelize):
    path = write_obj(tmp_path)
    v, t, attrs = hyvox.read_mesh(path, attributes=True)
    from_file = voxelize_as_read(v, t, attrs)
    from_arrays = voxelize_arrays([pixels(), None])
    assert np.array_equal(from_file.coords(), from_arrays.coords())
    colors = from_arrays.attributes()["color"]
    assert np.array_equal(from_file.attributes()["color"], colors)

    # The oracle, part by part (no voxel holds both): the image at the quad's UVs, Kd on the triangle.
    grid = from_arrays
    vertices, triangles, uvs, _, palette = arrays()
    texels = srgb_to_linear(pixels() / 255.0)
    quad_ijk, quad = voxel_attributes(
        vertices, triangles[:2], grid.origin, grid.voxel_size, grid.dims, uvs=uvs, texture=texels
    )
    plain_ijk, plain = voxel_attributes(
        vertices, triangles[2:], grid.origin, grid.voxel_size, grid.dims, material_ids=[1], palette=palette
    )
    oracle_keys = np.concatenate([by_key(quad_ijk, grid.dims), by_key(plain_ijk, grid.dims)])
    oracle = np.concatenate([quad["color"], plain["color"]])
    keys = by_key(grid.coords(), grid.dims)
    assert len(set(by_key(quad_ijk, grid.dims)) & set(by_key(plain_ijk, grid.dims))) == 0
    order, oracle_order = np.argsort(keys), np.argsort(oracle_keys)
    assert np.array_equal(keys[order], oracle_keys[oracle_order])
    np.testing.assert_allclose(colors[order], oracle[oracle_order], rtol=0, atol=2 / 255)
    assert colors[:, 0].std() > 0.05  # the image's texels, not one flat colour

    # The CLI takes the materials from the file by itself (no --texture).
    out = tmp_path / "scene.vdb"
    done = cli_voxelize(path, out, "-q", "--resolution", RESOLUTION, "--attributes", "color")
    assert done.returncode == 0, done.stderr
    assert "warning" not in done.stderr
    written = {tuple(item["min"]): item["value"] for item in vdb.read(str(out), "color").iterOnValues()}
    assert len(written) == grid.voxel_count
    got = np.array([written[tuple(int(c) for c in ijk)] for ijk in grid.coords()])
    np.testing.assert_array_equal(got, colors)


def test_a_missing_image_is_a_warning_and_the_material_keeps_its_kd(tmp_path, cli_voxelize):
    path = write_obj(tmp_path, image="missing.png", write_image=False)
    with pytest.warns(UserWarning, match="missing.png.*cannot be opened"):
        v, t, attrs = hyvox.read_mesh(path, attributes=True)
    assert attrs["textures"] == [None, None]
    grid = voxelize_as_read(v, t, attrs)
    colors = grid.attributes()["color"]
    on_quad = grid.coords()[:, 0] < 5 * RESOLUTION / 9  # the quad's voxels (x < 5 world units)
    np.testing.assert_allclose(colors[on_quad], np.tile(PAINTED_KD, (on_quad.sum(), 1)), atol=1e-6)
    np.testing.assert_allclose(colors[~on_quad], np.tile(PLAIN_KD, ((~on_quad).sum(), 1)), atol=1e-6)

    done = cli_voxelize(path, tmp_path / "out.vdb", "-q", "--resolution", RESOLUTION, "--attributes", "color")
    assert done.returncode == 0, done.stderr
    assert "warning" in done.stderr and "missing.png" in done.stderr


def test_a_missing_or_broken_mtl_is_a_warning_and_grey(tmp_path):
    path = write_obj(tmp_path, write_mtl=False)
    with pytest.warns(UserWarning, match="scene.mtl"):
        _, _, attrs = hyvox.read_mesh(path, attributes=True)
    np.testing.assert_array_equal(attrs["palette"], np.full((2, 3), 0.8, np.float32))
    assert attrs["textures"] == [None, None]

    (tmp_path / "scene.mtl").write_text("newmtl painted\nKd 0.5 x 0.5\n")
    with pytest.warns(UserWarning, match="line 2"):
        _, _, attrs = hyvox.read_mesh(path, attributes=True)
    np.testing.assert_array_equal(attrs["palette"], np.full((2, 3), 0.8, np.float32))


def test_geometry_alone_reads_without_warnings(tmp_path, recwarn):
    path = write_obj(tmp_path, write_mtl=False)
    v, t = hyvox.read_mesh(path)
    assert len(t) == 3 and len(recwarn) == 0


def test_textures_must_match_the_palette(tmp_path):
    with pytest.raises(ValueError, match="one entry .* per palette colour"):
        voxelize_arrays([pixels()], resolution=8)
    with pytest.raises(ValueError, match="texture must be a path or an array"):
        voxelize_arrays([7, None], resolution=8)
    with pytest.raises(ValueError, match="needs the mesh's UVs"):
        voxelize_arrays([pixels(), None], resolution=8, with_uvs=False)


def test_the_tessellation_refuses_a_texture_per_material():
    with pytest.raises(ValueError, match="not one per material"):
        voxelize_arrays([pixels(), None], resolution=8, method="tessellation")
