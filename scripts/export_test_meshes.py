#!/usr/bin/python3
"""Exports BOP PLY models (in mm) to the mesh formats robots' URDFs use, in metres, for the tests
of the model loader (test_mesh_formats_real_data.cpp): per model OBJ (with its .mtl), binary STL
with the origin moved by --offset, COLLADA (Z_UP, the faces split over two nodes, the second
placed by a translation) and, with assimp-utils' `assimp` on PATH, GLB (from the OBJ). Writes
offsets.json: the offset (metres) added to every vertex of each file, so that a pose of the model
in a file maps to the PLY's as t_ply = t_file + R offset.

Usage: scripts/export_test_meshes.py --out DIR PLY... [--offset X Y Z]
The output folder must be outside the models' dataset and the repository's tracked files (it is
generated data; build/ is fine).
"""
import argparse
import json
import pathlib
import shutil
import subprocess
import sys

import numpy as np

PLY_TYPES = {"char": "i1", "uchar": "u1", "int8": "i1", "uint8": "u1", "short": "i2",
             "ushort": "u2", "int16": "i2", "uint16": "u2", "int": "i4", "uint": "u4",
             "int32": "i4", "uint32": "u4", "float": "f4", "float32": "f4", "double": "f8",
             "float64": "f8"}


def read_ply(path):
    """Vertices (n x 3 float64) and triangles (m x 3 int) of an ascii or little-endian PLY whose
    faces are `list uchar int vertex_indices` triangles (BOP models)."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    fmt = next(line.split()[1] for line in header if line.startswith("format"))
    elements, props = [], {}
    for line in header:
        w = line.split()
        if w[0] == "element":
            elements.append((w[1], int(w[2])))
            props[w[1]] = []
        elif w[0] == "property" and w[1] != "list":
            props[elements[-1][0]].append((w[2], PLY_TYPES[w[1]]))
    counts = dict(elements)
    names = [n for n, _ in props["vertex"]]
    if fmt == "ascii":
        rows = data[end:].decode("ascii").split("\n")
        nv, nf = counts["vertex"], counts.get("face", 0)
        vert = np.array([r.split() for r in rows[:nv]], dtype=np.float64)
        faces = np.array([r.split() for r in rows[nv:nv + nf]], dtype=np.int64)
        if nf and (faces[:, 0] != 3).any():
            sys.exit(f"{path}: only triangle faces are supported")
        xyz = vert[:, [names.index(c) for c in "xyz"]]
        return xyz, faces[:, 1:4] if nf else np.zeros((0, 3), np.int64)
    if fmt != "binary_little_endian":
        sys.exit(f"{path}: format {fmt} is not supported")
    vtype = np.dtype([(n, "<" + t) for n, t in props["vertex"]])
    vert = np.frombuffer(data, vtype, counts["vertex"], end)
    ftype = np.dtype([("n", "u1"), ("i", "<i4", 3)])
    faces = np.frombuffer(data, ftype, counts.get("face", 0), end + vtype.itemsize * len(vert))
    if len(faces) and (faces["n"] != 3).any():
        sys.exit(f"{path}: only triangle faces are supported")
    xyz = np.stack([vert[c].astype(np.float64) for c in "xyz"], axis=1)
    return xyz, faces["i"].astype(np.int64)


def write_obj(path, v, f):
    mtl = path.with_suffix(".mtl")
    mtl.write_text("newmtl model\nKd 0.7 0.7 0.7\n")
    with path.open("w") as out:
        out.write(f"mtllib {mtl.name}\no model\nusemtl model\n")
        np.savetxt(out, v, fmt="v %.9g %.9g %.9g")
        np.savetxt(out, f + 1, fmt="f %d %d %d")


def write_binary_stl(path, v, f):
    tri = v[f].astype(np.float32)
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)
    rec = np.zeros(len(f), np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    rec["n"], rec["v"] = normals, tri
    with path.open("wb") as out:
        out.write(b"exported by stocs_ros scripts/export_test_meshes.py".ljust(80, b" "))
        out.write(np.uint32(len(f)).tobytes())
        out.write(rec.tobytes())


def dae_geometry(name, v, f):
    used, local = np.unique(f, return_inverse=True)
    pos = " ".join(f"{x:.9g}" for x in v[used].ravel())
    idx = " ".join(str(i) for i in local.ravel())
    return (f'<geometry id="{name}"><mesh>'
            f'<source id="{name}-pos"><float_array id="{name}-arr" count="{3 * len(used)}">'
            f'{pos}</float_array><technique_common><accessor source="#{name}-arr" '
            f'count="{len(used)}" stride="3"><param name="X" type="float"/>'
            '<param name="Y" type="float"/><param name="Z" type="float"/></accessor>'
            f'</technique_common></source><vertices id="{name}-vtx"><input semantic="POSITION" '
            f'source="#{name}-pos"/></vertices><triangles count="{len(f)}"><input '
            f'semantic="VERTEX" source="#{name}-vtx" offset="0"/><p>{idx}</p></triangles>'
            '</mesh></geometry>\n')


def write_dae(path, v, f, shift):
    """Z_UP, as CAD exports for URDFs: assimp turns it to Y-up in its root node, which rviz and
    the loader drop. The second half of the faces is stored shifted by -shift in a node translated
    by +shift, so the node transforms must be applied to get the model back."""
    half = len(f) // 2
    nodes = ('<node id="part1"><instance_geometry url="#geom1"/></node>'
             f'<node id="part2"><translate>{shift[0]:.9g} {shift[1]:.9g} {shift[2]:.9g}</translate>'
             '<instance_geometry url="#geom2"/></node>')
    path.write_text(
        '<?xml version="1.0" encoding="utf-8"?>\n'
        '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">\n'
        '<asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>\n'
        '<library_geometries>\n' + dae_geometry("geom1", v, f[:half]) +
        dae_geometry("geom2", v - shift, f[half:]) + '</library_geometries>\n'
        f'<library_visual_scenes><visual_scene id="scene">{nodes}</visual_scene>'
        '</library_visual_scenes>\n<scene><instance_visual_scene url="#scene"/></scene>\n'
        '</COLLADA>\n')


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True, type=pathlib.Path)
    parser.add_argument("--offset", nargs=3, type=float, default=[0.04, -0.03, 0.05],
                        help="metres added to the STL's vertices (its origin moves by -offset)")
    parser.add_argument("models", nargs="+", type=pathlib.Path, help="BOP PLY models in mm")
    args = parser.parse_args()
    repo = pathlib.Path(__file__).resolve().parent.parent
    out = args.out.resolve()
    inside = lambda folder: out == folder or folder in out.parents
    if (inside(repo) and not inside(repo / "build")) or any(
            inside(ply.resolve().parent.parent) for ply in args.models):
        sys.exit(f"export_test_meshes: {out} is inside the repository (outside build/) or the "
                 "models' dataset; write generated data elsewhere")
    out.mkdir(parents=True, exist_ok=True)
    offset = np.array(args.offset)
    assimp = shutil.which("assimp")
    offsets = {}
    for ply in args.models:
        v_mm, f = read_ply(ply)
        v = v_mm * 0.001
        stem = out / ply.stem
        write_obj(stem.with_suffix(".obj"), v, f)
        write_binary_stl(stem.with_suffix(".stl"), v + offset, f)
        write_dae(stem.with_suffix(".dae"), v, f, np.array([0.1, 0.2, -0.05]))
        offsets[stem.with_suffix(".stl").name] = offset.tolist()
        if assimp:
            subprocess.run([assimp, "export", str(stem.with_suffix(".obj")),
                            str(stem.with_suffix(".glb")), "-fglb2"], check=True,
                           stdout=subprocess.DEVNULL)
        print(f"{ply.name}: {len(v)} vertices, {len(f)} triangles -> {stem}.{{obj,stl,dae"
              f"{',glb' if assimp else ''}}}")
    (out / "offsets.json").write_text(json.dumps(offsets, indent=1) + "\n")


if __name__ == "__main__":
    main()
