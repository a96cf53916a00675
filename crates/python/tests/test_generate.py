"""generate, the Scene it returns, save/load/export/evaluate, and byte identity with the CLI."""

from __future__ import annotations

import json
import pathlib
import subprocess
import threading
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import scenethesis
from conftest import PROMPT, cli_binary


def test_scene_objects_are_typed_and_consistent(office: scenethesis.Scene) -> None:
    assert office.accepted is True
    assert office.prompt == PROMPT and office.seed == 1
    objects = office.objects
    assert len(objects) >= 5
    ids = [o.id for o in objects]
    assert len(set(ids)) == len(ids)
    categories = {o.category for o in objects}
    assert {"desk", "office_chair"} & categories or "desk" in categories, categories
    for o in objects:
        assert o.pose.shape == (4, 4) and o.pose.dtype == np.float64
        np.testing.assert_allclose(o.pose[3], [0, 0, 0, 1])
        assert o.bounds.shape == (2, 3)
        assert np.all(o.bounds[0] <= o.bounds[1])
        assert o.parent == "ground" or o.parent in ids or o.parent.startswith("wall")
    # The pose's translation is where the object stands: inside its own world bounds (x, z).
    for o in objects:
        x, _, z = o.pose[:3, 3]
        assert o.bounds[0][0] - 1e-6 <= x <= o.bounds[1][0] + 1e-6 or o.category == "rug"
        assert o.bounds[0][2] - 1e-6 <= z <= o.bounds[1][2] + 1e-6 or o.category == "rug"
    assert office.object(ids[0]).id == ids[0]
    with pytest.raises(KeyError):
        office.object("no_such_object")


def test_report_and_summary(office: scenethesis.Scene) -> None:
    report = office.report
    assert report is not None
    assert report["prompt"] == PROMPT and report["accepted"] is True
    assert report["objects"] == len(office.objects)
    assert "accepted" in (office.summary or "")
    scene_dict = office.to_dict()
    assert list(scene_dict["objects"]) == [o.id for o in office.objects]


def test_evaluate_matches_the_cli_and_the_judge(office: scenethesis.Scene, office_folder: pathlib.Path) -> None:
    # A folder is measured by the very code of `scenethesis eval --json`.
    from_folder = scenethesis.evaluate(office_folder)
    cli = json.loads(
        subprocess.run(
            [str(cli_binary()), "eval", str(office_folder), "--json"],
            check=True, capture_output=True, text=True,
        ).stdout
    )
    assert from_folder == cli
    # The saved folder (meshes read back from scene.glb) measures as the judge measured it.
    for key in ("col_o", "inst_o", "walk"):
        assert from_folder[key] == pytest.approx(office.report["verdict"]["metrics"][key], abs=1e-9), key
    # A scene in memory is measured on its own meshes, as the judge measured it.
    in_memory = office.evaluate()
    judged = office.report["verdict"]["metrics"]
    for key in ("objects", "categories", "col_o", "col_arch", "inst_o", "walk", "reach_floor"):
        assert in_memory[key] == pytest.approx(judged[key], abs=1e-9), key
    assert in_memory["col_o"] == 0 and in_memory["inst_o"] == 0 and in_memory["walk"] == 1.0


def test_save_then_load_round_trips(office: scenethesis.Scene, office_folder: pathlib.Path, tmp_path: pathlib.Path) -> None:
    assert sorted(p.name for p in office_folder.iterdir()) == ["report.json", "scene.glb", "scene.json"]
    loaded = scenethesis.load(office_folder)
    assert [o.id for o in loaded.objects] == [o.id for o in office.objects]
    for a, b in zip(loaded.objects, office.objects):
        np.testing.assert_array_equal(a.pose, b.pose)
    assert loaded.report == json.loads((office_folder / "report.json").read_text())
    again = tmp_path / "again"
    loaded.save(again)
    for name in ("scene.json", "scene.glb", "report.json"):
        assert (again / name).read_bytes() == (office_folder / name).read_bytes(), name


def test_exports_by_suffix(office: scenethesis.Scene, tmp_path: pathlib.Path) -> None:
    glb = office.export(tmp_path / "office.glb")
    assert glb == [str(tmp_path / "office.glb")]
    assert (tmp_path / "office.glb").read_bytes()[:4] == b"glTF"
    office.export(tmp_path / "office.usda")
    assert (tmp_path / "office.usda").read_text().startswith("#usda 1.0")
    office.export(tmp_path / "office.xml")
    mjcf = ET.parse(tmp_path / "office.xml").getroot()
    assert mjcf.tag == "mujoco"
    written = office.export(tmp_path / "robot.urdf")
    urdf = ET.parse(tmp_path / "robot.urdf").getroot()
    assert urdf.tag == "robot"
    meshes = tmp_path / "robot_meshes"
    assert str(meshes) in written and any(meshes.glob("*.obj"))
    files = {m.get("filename") for m in urdf.iter("mesh")}
    assert files and all(f.startswith("robot_meshes/") and (tmp_path / f).is_file() for f in files)
    with pytest.raises(ValueError, match="must end in"):
        office.export(tmp_path / "office.fbx")
    with pytest.raises(scenethesis.InvalidInputError, match="does not exist"):
        office.export(tmp_path / "missing" / "office.glb")


def test_python_and_cli_write_byte_identical_scenes(tmp_path: pathlib.Path) -> None:
    prompt, seed = "a bathroom with a bathtub", 2
    cli_out = tmp_path / "cli"
    subprocess.run(
        [str(cli_binary()), "generate", prompt, "--seed", str(seed), "--no-preview", "--out", str(cli_out)],
        check=True, capture_output=True,
    )
    py_out = tmp_path / "py"
    scenethesis.generate(prompt, seed, preview=False).save(py_out)
    for name in ("scene.json", "scene.glb"):
        assert (py_out / name).read_bytes() == (cli_out / name).read_bytes(), name
    cli_report = json.loads((cli_out / "report.json").read_text())
    py_report = json.loads((py_out / "report.json").read_text())
    for timing_free in ("prompt", "seed", "options_digest", "accepted", "objects", "verdict"):
        assert py_report[timing_free] == cli_report[timing_free], timing_free


def test_plan_edit_and_generate_from_it(tmp_path: pathlib.Path) -> None:
    plan = scenethesis.plan("a bedroom with a desk", seed=0)
    assert plan["prompt"] == "a bedroom with a desk"
    categories = [o["category"] for o in plan["objects"]]
    assert "bed" in categories and "desk" in categories
    path = tmp_path / "plan.json"
    path.write_text(json.dumps(plan))
    from_dict = scenethesis.generate(plan=plan, seed=0, preview=False, max_replans=0)
    from_file = scenethesis.generate(plan=path, seed=0, preview=False, max_replans=0)
    assert from_dict.to_dict() == from_file.to_dict()
    assert {o.category for o in from_dict.objects} >= {"bed", "desk"}


def test_progress_callback_sees_every_stage() -> None:
    events: list = []
    scenethesis.generate("a laundry room", seed=0, preview=False, progress=events.append)
    assert all(isinstance(e, scenethesis.ProgressEvent) for e in events)
    finished = [e.stage for e in events if e.event == "finished"]
    for stage in ("plan", "retrieve", "guide", "optimize", "judge"):
        assert stage in finished, (stage, finished)
    assert all(e.seconds >= 0 for e in events)


def test_progress_callback_errors_are_raised() -> None:
    def boom(event: scenethesis.ProgressEvent) -> None:
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        scenethesis.generate("a laundry room", seed=0, preview=False, progress=boom)


def test_threads_generate_in_parallel_with_the_gil_released() -> None:
    prompts = ["a garage", "a walk-in closet"]
    alone = {p: scenethesis.generate(p, 0, preview=False).to_dict() for p in prompts}
    results: dict = {}
    ticks = 0
    threads = [
        threading.Thread(target=lambda p=p: results.__setitem__(p, scenethesis.generate(p, 0, preview=False).to_dict()))
        for p in prompts
    ]
    for t in threads:
        t.start()
    while any(t.is_alive() for t in threads):
        ticks += 1  # runs only while the generating threads have released the GIL
        threading.Event().wait(0.001)
    for t in threads:
        t.join()
    assert results == alone
    assert ticks > 10


def test_previews_are_rgba_arrays(tmp_path: pathlib.Path) -> None:
    scene = scenethesis.generate("a small office with a desk and a chair", seed=1)
    assert scene.preview_names == ["preview.png", "preview_top.png"]
    image = scene.preview()
    assert image.dtype == np.uint8 and image.ndim == 3 and image.shape[2] == 4
    assert image[..., :3].std() > 5, "not a blank image"
    top = scene.preview("preview_top.png")
    assert top.ndim == 3 and top.shape[2] == 4
    scene.save(tmp_path / "with_previews")
    assert (tmp_path / "with_previews" / "preview.png").is_file()
    # A scene generated without previews is rendered on demand.
    bare = scenethesis.generate("a small office with a desk and a chair", seed=1, preview=False)
    assert bare.preview_names == []
    rendered = bare.preview(size=(320, 240))
    assert rendered.shape == (240, 320, 4)
