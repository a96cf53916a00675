"""The joint checks of check_exports.py: what each consumer makes of an articulated object.

For every object of scene.json with `joints`, and every door with a `leaf` (its one revolute
joint `leaf`, joined to the world, its glTF node under its wall's):
  * glTF: the object's node has a descendant node per joint whose extras carry the joint.
  * MuJoCo: a hinge (revolute) or slide (prismatic) joint `<object>_<joint>` with the joint's
    range (metres scaled by the pose) and initial qpos at the scene's state; left alone for 2 s
    no joint moves more than 0.01; then, one joint at a time from the loaded state, a PD force
    on qfrc_applied drives it to closed and then to its open limit: it must reach >= 90 % of its
    range, no free body other than what rides in the part may tilt by more than 10 degrees, and
    every object resting in a drawer (`parent_link`) must come out with it.
  * OpenUSD: the object's prim has PhysicsArticulationRootAPI, and a PhysicsRevoluteJoint (limits
    in degrees) or PhysicsPrismaticJoint (metres) per joint joins two rigid bodies.
  * URDF (yourdfpy): the robot loads and has a revolute or prismatic joint `<object>_<joint>_joint`
    with the joint's limits.
Each check reports through the `fail` / `ok` callables it is given.
"""

import math

TILT_DEGREES = 10.0
RIDE_FRACTION = 0.7


# A room door's leaf (docs/scene-json.md): one revolute joint named `leaf`, closed at 0 and
# opening to LEAF_OPEN_LIMIT rad into the room; its link is `<door>_leaf`, under the node of
# its wall in glTF.
LEAF_OPEN_LIMIT = 1.75


def articulated(scene):
    """Everything with joints, by id: objects with `joints`, and doors with a `leaf` (as an
    object-like dict whose one joint is the leaf's and whose glTF node is its wall's)."""
    out = {oid: obj for oid, obj in scene["objects"].items() if obj.get("joints")}
    for door in scene["architecture"].get("doors", []):
        leaf = door.get("leaf")
        if leaf is None:
            continue
        joint = {
            "name": "leaf",
            "kind": "revolute",
            "limits": [0.0, LEAF_OPEN_LIMIT],
            "opens_to": leaf["opens_to"],
            "state": leaf.get("state", 0.0),
        }
        out[door["id"]] = {"joints": [joint], "node": door["wall"], "door": True}
    return out


def model_units(obj, joint):
    """Joint values as MJCF, URDF and USD prismatic limits hold them: metres scaled by the pose."""
    return obj["pose"]["scale"] if joint["kind"] == "prismatic" else 1.0


def check_glb_joints(gltf, scene, fail, ok):
    nodes = gltf["nodes"]
    by_name = {n.get("name"): n for n in nodes}
    count = 0
    for oid, obj in articulated(scene).items():
        found = {}
        stack = list(by_name.get(obj.get("node", oid), {}).get("children", []))
        while stack:
            node = nodes[stack.pop()]
            joint = node.get("extras", {}).get("joint")
            if joint:
                found[joint["name"]] = joint
            stack.extend(node.get("children", []))
        for j in obj["joints"]:
            got = found.get(j["name"])
            if got is None or got["kind"] != j["kind"] or got["limits"] != j["limits"]:
                fail(f"glb: {oid} has no node for joint {j['name']} with its kind and limits ({got})")
            count += 1
    if count:
        ok(f"glb: {count} joint nodes with their joints in extras")


def riders(scene, oid, joint_name):
    """Objects resting on the part moved by `joint_name` of `oid`, and what rests on them."""
    out = {k for k, o in scene["objects"].items() if o["parent"] == oid and o.get("parent_link") == joint_name}
    grew = True
    while grew:
        more = {k for k, o in scene["objects"].items() if o["parent"] in out and k not in out}
        out |= more
        grew = bool(more)
    return out


def drive(model, data, mujoco, jid, open_value, touched=None):
    """Drives joint `jid` from where it is to 0 (0.5 s, skipped when it starts closed), then to
    `open_value` (1 s), then holds it there for 0.3 s. With a set `touched`, adds every body the
    joint's own body touches on the way."""
    dof = model.jnt_dofadr[jid]
    adr = model.jnt_qposadr[jid]
    inertia = 1.0 / max(model.dof_invweight0[dof], 1e-9)
    friction = model.dof_frictionloss[dof]
    start = data.qpos[adr]
    omega = 20.0
    closing = 0.5 if abs(start) > 1e-9 else 0.0
    steps = int(round((closing + 1.3) / model.opt.timestep))
    for _ in range(steps):
        t = data.time
        if t < closing:
            target = start * (1 - t / closing)
        else:
            target = open_value * min(1.0, (t - closing) / 1.0)
        err = target - data.qpos[adr]
        data.qfrc_applied[dof] = (
            inertia * (omega * omega * err - 2 * omega * data.qvel[dof])
            + data.qfrc_bias[dof]
            + friction * max(-1.0, min(1.0, err / 0.005))
        )
        mujoco.mj_step(model, data)
        if touched is not None:
            link = model.jnt_bodyid[jid]
            for c in data.contact[: data.ncon]:
                pair = (model.geom_bodyid[c.geom1], model.geom_bodyid[c.geom2])
                if link in pair:
                    touched.add(pair[1] if pair[0] == link else pair[0])
    data.qfrc_applied[dof] = 0.0
    return data.qpos[adr]


def up_tilt(data, b):
    """Degrees between a body's asset up (+Y, its MuJoCo frame's y axis) and world +Z."""
    up_z = data.xmat[b].reshape(3, 3)[2, 1]
    return math.degrees(math.acos(max(-1.0, min(1.0, up_z))))


def check_mjcf_joints(path, scene, fail, ok):
    import mujoco
    import numpy as np

    objects = articulated(scene)
    if not objects:
        return
    model = mujoco.MjModel.from_xml_path(str(path))
    body = lambda name: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
    kinds = {"revolute": mujoco.mjtJoint.mjJNT_HINGE, "prismatic": mujoco.mjtJoint.mjJNT_SLIDE}
    joints = []
    for oid, obj in objects.items():
        for j in obj["joints"]:
            name = f"{oid}_{j['name']}"
            jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, name)
            if jid < 0:
                fail(f"{path}: no joint {name}")
                continue
            unit = model_units(obj, j)
            if model.jnt_type[jid] != kinds[j["kind"]]:
                fail(f"{path}: joint {name} is of type {model.jnt_type[jid]}, expected {j['kind']}")
            want = np.array(j["limits"]) * unit
            if not model.jnt_limited[jid] or np.abs(model.jnt_range[jid] - want).max() > 1e-6:
                fail(f"{path}: joint {name} range {model.jnt_range[jid]} != {want}")
            q0 = model.qpos0[model.jnt_qposadr[jid]]
            if abs(q0 - j["state"] * unit) > 1e-6:
                fail(f"{path}: joint {name} starts at {q0}, scene.json's state is {j['state'] * unit}")
            joints.append((oid, j, jid, unit))
    free = [model.jnt_bodyid[k] for k in range(model.njnt) if model.jnt_type[k] == mujoco.mjtJoint.mjJNT_FREE]
    data = mujoco.MjData(model)

    # Left alone, no part moves.
    mujoco.mj_step(model, data, nstep=int(round(2.0 / model.opt.timestep)))
    for oid, j, jid, _ in joints:
        q = data.qpos[model.jnt_qposadr[jid]]
        if abs(q - model.qpos0[model.jnt_qposadr[jid]]) > 0.01:
            fail(f"{path}: joint {oid}_{j['name']} drifted from {model.qpos0[model.jnt_qposadr[jid]]:.4f} to {q:.4f} in 2 s")

    reached = []
    for oid, j, jid, unit in joints:
        mujoco.mj_resetData(model, data)
        mujoco.mj_forward(model, data)
        link = body(f"{oid}_{j['name']}")
        ride = {body(r) for r in riders(scene, oid, j["name"])}
        start = {b: data.xpos[b].copy() for b in free + [link]}
        tilt0 = {b: up_tilt(data, b) for b in free}
        lo, hi = model.jnt_range[jid]
        door = objects[oid].get("door", False)
        touched = set()
        q = drive(model, data, mujoco, jid, hi, touched=touched)
        if not np.all(np.isfinite(data.qpos)):
            fail(f"{path}: driving {oid}_{j['name']} diverged")
            continue
        frac = (q - 0.0) / (hi - 0.0)
        reached.append(f"{j['name']} {frac * 100:.0f}%")
        if frac < 0.9:
            fail(f"{path}: joint {oid}_{j['name']} reached {q:.4f} of its open limit {hi:.4f} ({frac * 100:.0f} %)")
        if door:
            # A room door swings into free floor: its leaf touches no object.
            for b in sorted(touched & set(free)):
                name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b)
                fail(f"{path}: opening {oid}_{j['name']} hit {name}")
        for b in free:
            # What a door leaf never touched (a ball rolling in its crate) is not its doing.
            if b in ride or (door and b not in touched):
                continue
            tilt = abs(up_tilt(data, b) - tilt0[b])
            if tilt > TILT_DEGREES:
                name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b)
                fail(f"{path}: opening {oid}_{j['name']} tipped {name} by {tilt:.1f} deg")
        if j["kind"] != "prismatic":
            continue
        moved = data.xpos[link] - start[link]
        travel = float(np.linalg.norm(moved))
        for b in ride:
            along = float(np.dot(data.xpos[b] - start[b], moved / max(travel, 1e-9)))
            if along < RIDE_FRACTION * travel:
                name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b)
                fail(f"{path}: {name} came out {along * 100:.1f} cm with {oid}_{j['name']} ({travel * 100:.1f} cm)")
    ok(f"mjcf joints: {len(joints)} joints still when left alone; driven open: {', '.join(reached)}")


def check_usd_joints(stage, by_id, scene, fail, ok):
    from pxr import UsdPhysics

    count = 0
    for oid, obj in articulated(scene).items():
        prim = by_id.get(oid)
        if prim is None:
            continue
        if not prim.HasAPI(UsdPhysics.ArticulationRootAPI):
            fail(f"usd: {oid} is not an articulation root")
        found = {}
        for child in prim.GetChildren():
            for kind, schema in (("revolute", UsdPhysics.RevoluteJoint), ("prismatic", UsdPhysics.PrismaticJoint)):
                if not child.IsA(schema):
                    continue
                joint = schema(child)
                targets = joint.GetBody1Rel().GetTargets() + joint.GetBody0Rel().GetTargets()
                bodies = [stage.GetPrimAtPath(t) for t in targets]
                # A door's leaf hangs on the world: no body0.
                want = 1 if obj.get("door") else 2
                if len(bodies) != want or not all(b and b.HasAPI(UsdPhysics.RigidBodyAPI) for b in bodies):
                    fail(f"usd: {child.GetPath()} does not join {want} rigid bodies ({targets})")
                    continue
                name = bodies[0].GetAttribute("scenethesis:joint").Get()
                found[name] = (kind, joint.GetLowerLimitAttr().Get(), joint.GetUpperLimitAttr().Get(), joint.GetAxisAttr().Get())
        for j in obj["joints"]:
            got = found.get(j["name"])
            unit = math.degrees(1.0) if j["kind"] == "revolute" else model_units(obj, j)
            want = [v * unit for v in j["limits"]]
            if got is None or got[0] != j["kind"] or abs(got[1] - want[0]) > 1e-3 or abs(got[2] - want[1]) > 1e-3:
                fail(f"usd: {oid} joint {j['name']}: expected {j['kind']} limits {want}, found {got}")
            count += 1
    if count:
        ok(f"usd: {count} physics joints with limits, articulation roots present")


def check_urdf_joints(path, scene, fail, ok):
    objects = articulated(scene)
    if not objects:
        return
    import yourdfpy

    robot = yourdfpy.URDF.load(str(path), build_scene_graph=False, load_meshes=False)
    count = 0
    for oid, obj in objects.items():
        for j in obj["joints"]:
            name = f"{oid}_{j['name']}_joint"
            joint = robot.joint_map.get(name)
            want = [v * model_units(obj, j) for v in j["limits"]]
            if joint is None or joint.type != j["kind"] or joint.limit is None:
                fail(f"{path}: yourdfpy finds no {j['kind']} joint {name}")
                continue
            if abs(joint.limit.lower - want[0]) > 1e-6 or abs(joint.limit.upper - want[1]) > 1e-6:
                fail(f"{path}: joint {name} limits {joint.limit.lower}..{joint.limit.upper} != {want}")
            count += 1
    ok(f"urdf: yourdfpy loaded {len(robot.link_map)} links, {count} revolute/prismatic joints with limits")
