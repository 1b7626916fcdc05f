# Unwraps a PRTM mesh (mesh_raw.md) with Blender's Smart UV Project or Lightmap Pack, the
# unwrappers the PRTT authors used, headless, and writes a PRTM mesh with UVs in [0, 1] (one
# vertex per triangle corner: Blender's UVs live on loops). Part of uv-atlas-eval.sh.
# Usage: blender -b --factory-startup --python blender_unwrap.py -- smart|lightmap IN OUT SIZE PADDING
import json
import struct
import sys
import time

import bpy


def read_mesh(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] != b"PRTM":
        raise SystemExit(f"{path}: not a PRTM mesh")
    n, t, _ = struct.unpack_from("<3I", data, 4)
    pos = struct.unpack_from(f"<{3 * n}f", data, 16)
    idx = struct.unpack_from(f"<{3 * t}I", data, 16 + 12 * n)
    verts = [pos[3 * i:3 * i + 3] for i in range(n)]
    faces = [idx[3 * i:3 * i + 3] for i in range(t)]
    return verts, faces


def write_mesh(path, positions, uvs):
    n = len(positions)
    with open(path, "wb") as f:
        f.write(b"PRTM" + struct.pack("<3I", n, n // 3, 1))
        f.write(struct.pack(f"<{3 * n}f", *[c for p in positions for c in p]))
        f.write(struct.pack(f"<{2 * n}f", *[c for uv in uvs for c in uv]))
        f.write(struct.pack(f"<{n}I", *range(n)))


def main():
    args = sys.argv[sys.argv.index("--") + 1:]
    method, src, dst, size, padding = args[0], args[1], args[2], int(args[3]), int(args[4])
    verts, faces = read_mesh(src)
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    mesh = bpy.data.meshes.new("m")
    mesh.from_pydata(verts, [], faces)
    obj = bpy.data.objects.new("m", mesh)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)
    start = time.perf_counter()
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    # island_margin is in UV units, but measured by the atlas check a margin of m leaves gaps
    # of only about m between islands at the atlas edges, half of them at 1/size: twice the
    # padding keeps every gap at or above it (docs/transfer-textures.md).
    margin = 2 * padding / size
    if method == "smart":
        bpy.ops.uv.smart_project(angle_limit=1.15192, island_margin=margin, area_weight=0.0,
                                 correct_aspect=True, scale_to_bounds=False)
    else:
        # PREF_MARGIN_DIV is the margin relative to each box (Lightmap Pack's own unit).
        bpy.ops.uv.lightmap_pack(PREF_CONTEXT="ALL_FACES", PREF_PACK_IN_ONE=True, PREF_NEW_UVLAYER=False,
                                 PREF_BOX_DIV=12, PREF_MARGIN_DIV=1.0)
    bpy.ops.object.mode_set(mode="OBJECT")
    seconds = time.perf_counter() - start
    uv = mesh.uv_layers.active.data
    positions, uvs = [], []
    for poly in mesh.polygons:
        for li in poly.loop_indices:
            positions.append(tuple(mesh.vertices[mesh.loops[li].vertex_index].co))
            # Blender's v points up, glTF's down: the check is symmetric, but keep glTF's convention.
            uvs.append((uv[li].uv[0], 1.0 - uv[li].uv[1]))
    write_mesh(dst, positions, uvs)
    print("RESULT " + json.dumps({"seconds": seconds, "faces": len(mesh.polygons), "input_faces": len(faces)}))


main()
