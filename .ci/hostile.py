#!/usr/bin/env python3
"""Replays the hostile inputs of issue #32 against a scenethesis binary.

Each case runs under a 4 GiB address-space limit and a 90 s wall-clock limit and must end with
exit code 0 or 1 (never a signal, a panic or an abort) and, when it fails, one clear error line.

    python3 .ci/hostile.py target/release/scenethesis [--only NAME] [--keep DIR]

Inputs are made in a temporary folder (a few hundred MB at most); nothing is downloaded. Prints
one line per case and a JSON summary; exits 1 when a case breaks the rule.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib
from pathlib import Path

LIMIT_BYTES = 4 << 30
LIMIT_SECONDS = 90


def png(width: int, height: int, rows: bytes, colour_type: int, depth: int) -> bytes:
    """A PNG from raw filtered rows (each row starts with its filter byte)."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def blank_png(width: int, height: int, colour_type: int = 2, depth: int = 8, fill: int = 0) -> bytes:
    channels = {0: 1, 2: 3}[colour_type]
    row = b"\x00" + bytes([fill]) * (width * channels * depth // 8)
    return png(width, height, row * height, colour_type, depth)


def npy(width: int, height: int, value: float, slope: float = 0.0) -> bytes:
    """A float32 depth map: `value` metres plus `slope` per row."""
    header = "{'descr': '<f4', 'fortran_order': False, 'shape': (%d, %d), }" % (height, width)
    header += " " * (63 - (len(header) + 10) % 64) + "\n"
    rows = b"".join(struct.pack("<f", value + slope * y) * width for y in range(height))
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode() + rows


class Case:
    def __init__(self, name: str, args: list[str], setup=None, stdin: bytes | None = None):
        self.name, self.args, self.setup, self.stdin = name, args, setup, stdin


def plan(base: dict, **changes) -> dict:
    out = json.loads(json.dumps(base))
    out.update(changes)
    return out


def renamed(base: dict, old: str, new: str) -> dict:
    """`base` with the object `old` (and every reference to it) renamed `new`."""
    out = plan(base)
    for o in out["objects"]:
        if o["id"] == old:
            o["id"] = new
        if o.get("parent") == old:
            o["parent"] = new
        for r in o.get("relations", []):
            if r.get("target") == old:
                r["target"] = new
    for c in out.get("constraints", []):
        if c.get("subject") == old:
            c["subject"] = new
        if c.get("target") == old:
            c["target"] = new
    if out["anchor"] == old:
        out["anchor"] = new
    return out


def cases(work: Path, binary: str) -> list[Case]:
    out_dir = str(work / "out")
    # A valid plan to mutate, from the offline planner.
    base_path = work / "base_plan.json"
    subprocess.run([binary, "plan", "a small office with a desk and a chair", "--out", str(base_path), "--force"],
                   check=True, capture_output=True)
    base = json.loads(base_path.read_text())
    objects = base["objects"]
    anchor = base["anchor"]

    def write_plan(name: str, value: dict) -> str:
        path = work / f"{name}.json"
        path.write_text(json.dumps(value))
        return str(path)

    def gen_plan(name: str, value: dict, *extra: str) -> Case:
        return Case(name, ["generate", "--plan", write_plan(name, value), "--out", out_dir, "--force", "--no-preview", *extra])

    self_parent = plan(base)
    child = next(o for o in self_parent["objects"] if o["id"] != anchor)
    child["parent"] = child["id"]
    child["support"] = "on"
    huge_room = plan(base, room_size=[1e6, 1e6])
    big_room = plan(base, room_size=[999, 999])
    tall = plan(base, wall_height=1e6)
    escaped = renamed(base, anchor, "\x1b[31mred\u202e\n" + "x" * 20)
    many = plan(base)
    template = next(o for o in objects if o["id"] != anchor and o.get("parent") == "ground")
    many["objects"] = [objects[0]] + [dict(template, id=f"extra_{i}", relations=[]) for i in range(60_000)]
    self_constraint = plan(base, constraints=[{"subject": anchor, "kind": "beside", "target": {"kind": "object", "id": anchor}, "phrase": "beside itself"}])
    long_id = renamed(base, anchor, "a" * 256)

    # Guidance: 640 x 480 images of a known camera, the lower half one desk.
    g = work / "guidance"
    g.mkdir()
    w, h = 640, 480
    (g / "rgb.png").write_bytes(blank_png(w, h, fill=128))
    ids_rows = b"".join(b"\x00" + struct.pack(">H", 1 if y > h // 2 else 0) * w for y in range(h))
    (g / "ids.png").write_bytes(png(w, h, ids_rows, 0, 16))
    (g / "labels.json").write_text(json.dumps({"1": {"id": "desk_0", "category": "desk"}}))
    camera = {"intrinsics": {"width": w, "height": h, "fx": 500.0, "fy": 500.0, "cx": 320.0, "cy": 240.0},
              "position": [0.0, 1.5, 3.0], "rotation": [-0.2588, 0.0, 0.0, 0.9659]}
    (g / "camera.json").write_text(json.dumps(camera))
    (g / "depth.npy").write_bytes(npy(w, h, 2.0, slope=0.004))

    def guided(name: str, **files: bytes | str) -> Case:
        d = work / name
        shutil.copytree(g, d)
        for file, content in files.items():
            file = file.replace("_", ".", 1) if file.count("_") == 1 else file
            (d / file).write_bytes(content if isinstance(content, bytes) else content.encode())
        return Case(name, ["generate", "a small office with a desk and a chair", "--guide", "vision",
                           "--guide-image", str(d / "rgb.png"), "--guide-masks", str(d / "ids.png"),
                           "--guide-labels", str(d / "labels.json"), "--guide-depth", str(d / "depth.npy"),
                           "--camera", str(d / "camera.json"), "--out", out_dir, "--force", "--no-preview"])

    many_labels = {str(v): {"id": f"desk_{v}", "category": "desk"} for v in range(1, 65536)}
    dup_labels = '{"1": {"id": "desk_0", "category": "desk"}, "1": {"id": "chair_0", "category": "chair"}}'
    bidi_labels = json.dumps({"1": {"id": "desk\u202e0", "category": "desk"}})
    long_label = json.dumps({"1": {"id": "d" * 10_000_000, "category": "desk"}})
    big = 8192
    far_camera = dict(camera, position=[1e300, 1.5, 3.0])
    zero_q = dict(camera, rotation=[0.0, 0.0, 0.0, 0.0])
    down = dict(camera, rotation=[-0.7071, 0.0, 0.0, 0.7071], position=[0.0, 30.0, 0.0])
    extreme = dict(camera, intrinsics=dict(camera["intrinsics"], fx=1e-9, fy=1e-9))

    # Assets: one OBJ of 4.9 million identical triangles.
    assets = work / "assets"
    assets.mkdir()

    def write_obj() -> None:
        with open(assets / "desk.obj", "w") as f:
            f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
            f.write("f 1 2 3\n" * 4_900_000)

    prompts = work / "prompts.txt"
    long_prompt = work / "long_prompt.txt"

    return [
        gen_plan("01_self_parent", self_parent),
        gen_plan("02_room_1e6", huge_room),
        gen_plan("02_room_999", big_room),
        guided("03_many_labels", labels_json=json.dumps(many_labels)),
        guided("04_8192_images", rgb_png=blank_png(big, big), ids_png=png(big, big, (b"\x00" + b"\x00\x00" * big) * big, 0, 16),
               depth_npy=npy(big, big, 2.5), camera_json=json.dumps(dict(camera, intrinsics={"width": big, "height": big, "fx": 6400.0, "fy": 6400.0, "cx": 4096.0, "cy": 4096.0}))),
        guided("05_constant_depth", depth_npy=npy(w, h, 2.5)),
        guided("05_camera_down_far", camera_json=json.dumps(down)),
        guided("05_extreme_intrinsics", camera_json=json.dumps(extreme)),
        guided("06_camera_1e300", camera_json=json.dumps(far_camera).replace("1e+300", "1e300")),
        guided("06_zero_quaternion", camera_json=json.dumps(zero_q)),
        gen_plan("07_escaped_id", escaped),
        gen_plan("08_60000_objects", many),
        Case("11_batch_1e8_seeds", ["batch", str(prompts), "--out", str(work / "batch"), "--seeds", "100000000", "--no-preview"],
             setup=lambda: prompts.write_text("a kitchen\n")),
        gen_plan("12_urdf_256_byte_id", long_id, "--export", "urdf,usd,mjcf"),
        Case("13_llm_config_dev_zero", ["generate", "a kitchen", "--planner", "llm", "--llm-config", "/dev/zero", "--out", out_dir, "--force", "--no-preview"]),
        Case("14_degenerate_obj", ["generate", "a small office with a desk", "--assets", str(assets), "--out", out_dir, "--force", "--no-preview"],
             setup=write_obj),
        Case("16_50mb_batch_prompt", ["batch", str(long_prompt), "--out", str(work / "batch16"), "--no-preview", "--max-replans", "0"],
             setup=lambda: long_prompt.write_text("a kitchen with a table " * 2_200_000 + "\n")),
        guided("17_duplicate_labels", labels_json=dup_labels),
        guided("17_bidi_label", labels_json=bidi_labels),
        guided("17_10mb_label", labels_json=long_label),
        gen_plan("18_self_constraint", self_constraint),
        gen_plan("18_wall_height_1e6", tall),
    ]


def limit() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (LIMIT_BYTES, LIMIT_BYTES))


def run(case: Case, binary: str) -> dict:
    if case.setup:
        case.setup()
    out = Path(case.args[case.args.index("--out") + 1]) if "--out" in case.args else None
    if out is not None:
        shutil.rmtree(out, ignore_errors=True)
    started = time.monotonic()
    try:
        proc = subprocess.run([binary, *case.args], capture_output=True, timeout=LIMIT_SECONDS, preexec_fn=limit)
        code, stderr = proc.returncode, proc.stderr.decode(errors="replace")
    except subprocess.TimeoutExpired as e:
        code, stderr = "timeout", (e.stderr or b"").decode(errors="replace")
    seconds = time.monotonic() - started
    lines = stderr.splitlines()
    first = next((i for i, line in enumerate(lines) if line.startswith("error")), None)
    # The error and the causes the CLI prints under it, as one line.
    errors = [] if first is None else [" / ".join(line.strip() for line in lines[first:first + 4])]
    ok = code in (0, 1) and "panicked" not in stderr and (code == 0 or len(errors) >= 1)
    if ok and code == 0 and out is not None and (out / "scene.json").is_file():
        # A scene reported written must be one the tool's own validator accepts.
        check = subprocess.run([binary, "validate", str(out)], capture_output=True, timeout=LIMIT_SECONDS)
        if check.returncode != 0:
            ok, errors = False, ["validate refused the scene: " + check.stderr.decode(errors="replace").strip()]
    return {"case": case.name, "exit": code, "seconds": round(seconds, 1), "ok": ok,
            "error": errors[0][:300] if errors else "", "warnings": sum(1 for l in stderr.splitlines() if l.startswith("warning"))}


def main() -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument("binary")
    parser.add_argument("--only")
    parser.add_argument("--keep")
    args = parser.parse_args()
    binary = os.path.abspath(args.binary)
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="hostile-"))
    work.mkdir(parents=True, exist_ok=True)
    results = []
    try:
        for case in cases(work, binary):
            if args.only and args.only not in case.name:
                continue
            result = run(case, binary)
            results.append(result)
            mark = "ok " if result["ok"] else "BAD"
            print(f"{mark} {case.name:28} exit {result['exit']!s:8} {result['seconds']:6.1f} s  {result['error']}", flush=True)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    print(json.dumps(results))
    return 0 if all(r["ok"] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
