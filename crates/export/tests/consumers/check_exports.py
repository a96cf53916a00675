#!/usr/bin/env python3
"""Checks a scenethesis output folder with the tools that really consume it.

Usage: check_exports.py DIR [--seconds S] [--tolerance M]

DIR must hold scene.json and the exports (scene.glb, scene.usda, scene.mjcf.xml, scene.urdf +
meshes/). Checks:
  * glTF: the GLB header and JSON chunk are well formed and the scene's root nodes are one per
    architecture piece (floor, walls, window panes), named by its id, then in a house one per
    room holding that room's objects, then one per object in no room.
  * OpenUSD (pip: usd-core): Usd.Stage.Open succeeds, upAxis is Y, metersPerUnit is 1, every
    object is an Xform whose world bounding box matches scene.json's world_aabb.
  * MuJoCo (pip: mujoco): MjModel.from_xml_path loads the MJCF, every body starts where
    scene.json puts it, exactly the objects mounted on a wall (support `mounted`, parent a wall
    id) are welded (no joint) and every other one has a free joint, and after simulating S
    seconds (default 2) every free body moved less than M metres (default 0.01) and nothing
    became NaN.
  * URDF: the XML parses, every link named by an object id exists, every mesh file exists,
    mounted objects hang from `world` on a fixed joint and the others on floating ones.
  * Textures (every scene's floor and walls wear library materials): the GLB embeds PNG images
    that its materials use as base-colour, metallic-roughness and normal textures, every
    textured primitive has TEXCOORD_0; OpenUSD finds UsdUVTexture shaders whose files exist;
    MuJoCo loads at least one texture (ntex > 0); the URDF's texture files exist.
  * Joints (check_joints.py, for objects with `joints`): each format has them with their limits;
    MuJoCo drives each open and what rides in a drawer comes out with it; yourdfpy (pip:
    yourdfpy) loads the URDF.
Exits 1 with one line per failure when anything is wrong.
"""

import argparse
import json
import math
import struct
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import check_joints

failures = []


def fail(msg):
    failures.append(msg)
    print(f"FAIL {msg}", flush=True)


def ok(msg):
    print(f"ok   {msg}", flush=True)


def architecture_ids(scene):
    arch = scene["architecture"]
    walls = [w["id"] for w in arch.get("walls", [])]
    windows = [w["id"] for w in arch.get("windows", [])]
    return [arch["floor"]["id"]] + walls + windows


def glb_root_ids(scene):
    """The GLB's root node names: the architecture pieces, in a house one node per room, then
    the objects in no room of the house."""
    rooms = [r["id"] for r in scene["architecture"].get("rooms", [])]
    loose = [k for k, o in scene["objects"].items() if o.get("room") not in rooms]
    return architecture_ids(scene) + rooms + loose


def check_glb_rooms(path, gltf, scene):
    """Each room node holds exactly the nodes of the objects whose `room` it is."""
    nodes = gltf["nodes"]
    for room in scene["architecture"].get("rooms", []):
        node = next((n for n in nodes if n.get("name") == room["id"]), None)
        held = sorted(nodes[i]["name"] for i in (node or {}).get("children", []))
        want = sorted(k for k, o in scene["objects"].items() if o.get("room") == room["id"])
        if node is None or held != want:
            fail(f"{path}: room node {room['id']} holds {held}, expected {want}")
        else:
            ok(f"glb: room {room['id']} holds its {len(want)} objects")


def check_glb(path, scene):
    data = path.read_bytes()
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67 or version != 2 or length != len(data):
        fail(f"{path}: bad GLB header (magic {magic:#x}, version {version}, length {length})")
        return
    json_len, json_type = struct.unpack_from("<II", data, 12)
    if json_type != 0x4E4F534A:
        fail(f"{path}: first chunk is not JSON")
        return
    gltf = json.loads(data[20 : 20 + json_len])
    roots = gltf["scenes"][gltf.get("scene", 0)]["nodes"]
    names = [gltf["nodes"][i].get("name") for i in roots]
    expected = glb_root_ids(scene)
    if names != expected:
        fail(f"{path}: node names {names} != ids {expected}")
    else:
        ok(f"glb: {len(names)} root nodes named by id, {len(gltf['materials'])} materials")
    check_glb_rooms(path, gltf, scene)
    check_glb_textures(path, gltf, data[20 + json_len + 8 :])
    check_joints.check_glb_joints(gltf, scene, fail, ok)


def check_glb_textures(path, gltf, bin_chunk):
    images = gltf.get("images", [])
    views = gltf["bufferViews"]
    bad = [i for i, im in enumerate(images)
           if bin_chunk[views[im["bufferView"]]["byteOffset"]:][:8] != b"\x89PNG\r\n\x1a\n"]
    if not images or bad:
        fail(f"{path}: {len(images)} embedded images, not PNG: {bad[:5]}")
        return
    textures = gltf.get("textures", [])

    def imported(m):
        # An imported image (`image_<digest>`) is a base-colour texture alone.
        index = m["pbrMetallicRoughness"]["baseColorTexture"]["index"]
        return images[textures[index]["source"]].get("name", "").startswith("image_")

    textured = [m for m in gltf["materials"] if "baseColorTexture" in m.get("pbrMetallicRoughness", {})]
    full = [m for m in textured
            if imported(m)
            or ("metallicRoughnessTexture" in m["pbrMetallicRoughness"] and "normalTexture" in m)]
    if not textured or len(full) != len(textured):
        fail(f"{path}: {len(textured)} materials with a base-colour texture, {len(full)} with all three maps")
    textured_ids = {i for i, m in enumerate(gltf["materials"]) if m in textured}
    missing_uv = [mesh["name"] for mesh in gltf["meshes"] for p in mesh["primitives"]
                  if p["material"] in textured_ids and "TEXCOORD_0" not in p["attributes"]]
    if missing_uv:
        fail(f"{path}: textured primitives without TEXCOORD_0 in {missing_uv[:5]}")
    names = [im.get("name", "") for im in images]
    if len(set(names)) != len(names):
        fail(f"{path}: an image is embedded more than once: {sorted(names)}")
    ok(f"glb: {len(images)} embedded PNG textures (once each), {len(textured)} textured materials")


def check_usd(path, scene, tolerance):
    from pxr import Usd, UsdGeom

    stage = Usd.Stage.Open(str(path))
    if stage is None:
        fail(f"{path}: Usd.Stage.Open returned None")
        return
    if UsdGeom.GetStageUpAxis(stage) != UsdGeom.Tokens.y:
        fail(f"{path}: upAxis is {UsdGeom.GetStageUpAxis(stage)}, expected Y")
    if UsdGeom.GetStageMetersPerUnit(stage) != 1.0:
        fail(f"{path}: metersPerUnit is {UsdGeom.GetStageMetersPerUnit(stage)}")
    by_id = {}
    for prim in stage.Traverse():
        attr = prim.GetAttribute("scenethesis:id")
        if attr and attr.HasValue():
            by_id[attr.Get()] = prim
    cache = UsdGeom.BBoxCache(Usd.TimeCode.Default(), [UsdGeom.Tokens.default_])
    meshes = sum(1 for p in stage.Traverse() if p.IsA(UsdGeom.Mesh))
    worst = 0.0
    for oid, obj in scene["objects"].items():
        prim = by_id.get(oid)
        if prim is None or not prim.IsA(UsdGeom.Xform):
            fail(f"{path}: no Xform for object {oid}")
            continue
        box = cache.ComputeWorldBound(prim).ComputeAlignedRange()
        lo, hi = box.GetMin(), box.GetMax()
        want = obj["world_aabb"]
        err = max(
            max(abs(lo[k] - want["min"][k]) for k in range(3)),
            max(abs(hi[k] - want["max"][k]) for k in range(3)),
        )
        worst = max(worst, err)
        if err > tolerance:
            fail(f"{path}: {oid} bounds {list(lo)}..{list(hi)} differ from scene.json {want} by {err:.4f} m")
    ok(f"usd: stage opened, Y up, {len(by_id)} prims with ids, {meshes} meshes, worst bounds error {worst * 1000:.2f} mm")
    check_usd_textures(path, stage)
    check_joints.check_usd_joints(stage, by_id, scene, fail, ok)


def check_usd_textures(path, stage):
    from pxr import UsdShade

    files, missing = set(), []
    for prim in stage.Traverse():
        shader = UsdShade.Shader(prim)
        if not shader or shader.GetIdAttr().Get() != "UsdUVTexture":
            continue
        asset = shader.GetInput("file").Get()
        resolved = asset.resolvedPath if asset is not None else ""
        if not resolved or not Path(resolved).exists():
            missing.append(str(asset))
        files.add(resolved)
    if not files or missing:
        fail(f"{path}: {len(files)} UsdUVTexture files, unresolved or missing: {missing[:5]}")
    else:
        ok(f"usd: {len(files)} UsdUVTexture files, all present")


def z_up(p):
    return (p[0], -p[2], p[1])


def mounted_ids(scene):
    """The objects scene.json says hang on a wall: support `mounted`, parent a wall id."""
    walls = {w["id"] for w in scene["architecture"].get("walls", [])}
    out = set()
    for oid, obj in scene["objects"].items():
        if obj["support"] == "mounted":
            if obj["parent"] not in walls:
                fail(f"scene.json: {oid} is mounted on {obj['parent']!r}, which is not a wall")
            out.add(oid)
        elif obj["parent"] in walls:
            fail(f"scene.json: {oid} names wall {obj['parent']} as parent with support {obj['support']}")
    return out


def check_mjcf(path, scene, seconds, tolerance):
    import mujoco
    import numpy as np

    model = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    free_bodies = []
    for j in range(model.njnt):
        if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE:
            free_bodies.append(model.jnt_bodyid[j])
    names = {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b): b for b in range(1, model.nbody)}
    mounted = mounted_ids(scene)
    free_set = set(free_bodies)
    for oid, obj in scene["objects"].items():
        b = names.get(oid)
        if b is None:
            fail(f"{path}: no body named {oid}")
            continue
        if (oid in mounted) == (b in free_set):
            fail(f"{path}: body {oid} is {'free' if b in free_set else 'welded'}, but scene.json says "
                 f"{'mounted' if oid in mounted else 'not mounted'}")
        want = np.array(z_up(obj["pose"]["translation"]))
        if np.linalg.norm(data.xpos[b] - want) > 1e-4:
            fail(f"{path}: body {oid} starts at {data.xpos[b]}, scene.json says {want}")
    start = {b: data.xpos[b].copy() for b in free_bodies}
    start_quat = {b: data.xquat[b].copy() for b in free_bodies}
    steps = int(round(seconds / model.opt.timestep))
    mujoco.mj_step(model, data, nstep=steps)
    if not np.all(np.isfinite(data.qpos)):
        fail(f"{path}: simulation diverged (NaN in qpos)")
        return
    moves = []
    for b in free_bodies:
        name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b)
        d = float(np.linalg.norm(data.xpos[b] - start[b]))
        q0, q1 = start_quat[b], data.xquat[b]
        angle = math.degrees(2 * math.acos(min(1.0, abs(float(np.dot(q0, q1))))))
        moves.append((d, angle, name))
        if d >= tolerance:
            fail(f"{path}: {name} moved {d * 100:.2f} cm (turned {angle:.1f} deg) in {seconds} s of simulation")
    moves.sort(reverse=True)
    top = ", ".join(f"{n} {d * 1000:.1f} mm" for d, _, n in moves[:3])
    if model.ntex == 0 or not np.any(model.mat_texid >= 0):
        fail(f"{path}: {model.ntex} textures, no material uses one")
    ok(
        f"mjcf: {model.ntex} textures, {model.nmat} materials; loaded {model.nbody - 1} bodies ({len(free_bodies)} free, {len(mounted)} welded "
        f"mounted), {model.ngeom} geoms; "
        f"after {seconds} s largest moves: {top}"
    )
    check_joints.check_mjcf_joints(path, scene, fail, ok)


def check_urdf(path, scene):
    root = ET.parse(path).getroot()
    links = {l.get("name") for l in root.findall("link")}
    joints = root.findall("joint")
    for oid in scene["objects"]:
        if oid not in links:
            fail(f"{path}: no link named {oid}")
    missing = []
    for mesh in root.iter("mesh"):
        f = path.parent / mesh.get("filename")
        if not f.exists():
            missing.append(str(f))
    if missing:
        fail(f"{path}: missing mesh files {missing[:5]}")
    textures = [path.parent / t.get("filename") for t in root.iter("texture")]
    if not textures or not all(t.exists() for t in textures):
        fail(f"{path}: {len(textures)} texture files, missing {[str(t) for t in textures if not t.exists()][:5]}")
    mounted = mounted_ids(scene)
    kinds = {j.find("child").get("link"): j.get("type") for j in joints if j.find("child") is not None}
    for oid in scene["objects"]:
        want = "fixed" if oid in mounted else "floating"
        if kinds.get(oid) != want:
            fail(f"{path}: joint of {oid} is {kinds.get(oid)}, expected {want}")
    ok(f"urdf: {len(links)} links, {len(joints)} joints, all mesh files present, {len(textures)} texture references")
    check_joints.check_urdf_joints(path, scene, fail, ok)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", type=Path)
    ap.add_argument("--seconds", type=float, default=2.0)
    ap.add_argument("--tolerance", type=float, default=0.01)
    args = ap.parse_args()
    scene = json.loads((args.dir / "scene.json").read_text())
    checks = [
        ("scene.glb", lambda p: check_glb(p, scene)),
        ("scene.usda", lambda p: check_usd(p, scene, args.tolerance)),
        ("scene.mjcf.xml", lambda p: check_mjcf(p, scene, args.seconds, args.tolerance)),
        ("scene.urdf", lambda p: check_urdf(p, scene)),
    ]
    for name, check in checks:
        path = args.dir / name
        if not path.exists():
            fail(f"{path} does not exist")
            continue
        try:
            check(path)
        except Exception as e:  # a consumer refusing the file is a failure, not a crash
            fail(f"{path}: {type(e).__name__}: {e}")
    if failures:
        print(f"{len(failures)} export check(s) failed for {args.dir}", file=sys.stderr)
        sys.exit(1)
    print(f"all export checks passed for {args.dir}")


if __name__ == "__main__":
    main()
