# Lays out a lightmap atlas with Blender's Smart UV Project, run headless by prt-bake
# (baker/unwrap/uv_unwrap.h); embedded into the binary at build time, so an installed prt-bake
# needs no source tree. Reads a PRTM mesh without UVs (bench/uv_atlas/mesh_raw.md) and writes
# one with a vertex per triangle corner (Blender keeps UVs on loops) in the input's triangle
# order, with glTF's v-down UVs.
# Usage: blender -b --factory-startup --python-exit-code 3 --python THIS -- IN OUT MARGIN
import array
import struct
import sys

import bpy


def read_mesh(path):
    with open(path, "rb") as f:
        data = f.read()
    if len(data) < 16 or data[:4] != b"PRTM":
        raise RuntimeError(f"{path}: not a PRTM mesh")
    n, t, has_uv = struct.unpack_from("<3I", data, 4)
    if has_uv != 0 or len(data) != 16 + 12 * n + 12 * t:
        raise RuntimeError(f"{path}: the header's counts do not match the file size")
    pos = array.array("f", data[16:16 + 12 * n])
    idx = array.array("I", data[16 + 12 * n:])
    if sys.byteorder != "little":
        pos.byteswap()
        idx.byteswap()
    return pos, idx


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    src, dst, margin = args[0], args[1], float(args[2])
    pos, idx = read_mesh(src)
    n, t = len(pos) // 3, len(idx) // 3
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    mesh = bpy.data.meshes.new("atlas")
    mesh.from_pydata([pos[3 * i:3 * i + 3] for i in range(n)], [], [idx[3 * i:3 * i + 3] for i in range(t)])
    obj = bpy.data.objects.new("atlas", mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    # Angle limit 66 degrees, no area weighting, islands kept at their scale (the evaluation's
    # settings, docs/transfer-textures.md). island_margin is in UV units of the layout before
    # packing scales it, so the caller checks the gutter in texels and retries with a larger one.
    bpy.ops.uv.smart_project(angle_limit=1.15192, island_margin=margin, area_weight=0.0,
                             correct_aspect=True, scale_to_bounds=False)
    bpy.ops.object.mode_set(mode="OBJECT")
    # The caller maps corners back to its vertices and checks their positions: the faces must
    # be the input's triangles, in its order, as Blender wrote them (loops in face order).
    if len(mesh.polygons) != t or len(mesh.loops) != 3 * t:
        raise RuntimeError(f"Blender made {len(mesh.polygons)} faces, {len(mesh.loops)} corners of {t} triangles")
    starts = array.array("i", [0]) * t
    mesh.polygons.foreach_get("loop_start", starts)
    if any(starts[i] != 3 * i for i in range(t)):
        raise RuntimeError("Blender reordered the triangles' corners")
    corners = array.array("i", [0]) * (3 * t)
    mesh.loops.foreach_get("vertex_index", corners)
    co = array.array("f", [0.0]) * (3 * len(mesh.vertices))
    mesh.vertices.foreach_get("co", co)
    out_pos = array.array("f", [0.0]) * (9 * t)
    for c in range(3 * t):
        v = corners[c]
        out_pos[3 * c:3 * c + 3] = co[3 * v:3 * v + 3]
    uv = array.array("f", [0.0]) * (6 * t)
    mesh.uv_layers.active.data.foreach_get("uv", uv)
    for k in range(1, len(uv), 2):
        uv[k] = 1.0 - uv[k]  # Blender's v points up, glTF's down
    out_idx = array.array("I", range(3 * t))
    if sys.byteorder != "little":
        for a in (out_pos, uv, out_idx):
            a.byteswap()
    with open(dst, "wb") as f:
        f.write(b"PRTM" + struct.pack("<3I", 3 * t, t, 1))
        f.write(out_pos.tobytes())
        f.write(uv.tobytes())
        f.write(out_idx.tobytes())


main()
