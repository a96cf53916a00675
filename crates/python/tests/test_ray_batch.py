"""The Ray example writes the same folders, byte for byte, as `scenethesis batch`."""

from __future__ import annotations

import json
import os
import pathlib
import subprocess
import sys

import pytest

from conftest import cli_binary

EXAMPLE = pathlib.Path(__file__).resolve().parents[1] / "examples" / "ray_batch.py"


def ray_available() -> bool:
    try:
        import ray  # noqa: F401
    except ImportError:
        if os.environ.get("SCENETHESIS_REQUIRE_RAY") == "1":
            raise
        return False
    return True


@pytest.mark.skipif(not ray_available(), reason="ray is not installed (pip install ray)")
def test_ray_batch_matches_the_cli_batch(tmp_path: pathlib.Path) -> None:
    prompts = tmp_path / "prompts.txt"
    prompts.write_text("# two rooms\na bathroom\n\na small office with a desk and a chair\n")
    cli_out, ray_out = tmp_path / "cli", tmp_path / "ray"
    subprocess.run(
        [str(cli_binary()), "batch", str(prompts), "--out", str(cli_out), "--seeds", "2", "--no-preview"],
        check=True, capture_output=True,
    )
    env = dict(os.environ, RAY_USAGE_STATS_ENABLED="0")
    env.pop("RAY_ADDRESS", None)
    run = subprocess.run(
        [sys.executable, str(EXAMPLE), str(prompts), "--out", str(ray_out), "--seeds", "2",
         "--no-preview", "--num-cpus", "2"],
        check=True, capture_output=True, text=True, env=env, timeout=900,
    )
    summary = json.loads(run.stdout.strip().splitlines()[-1])
    assert summary["jobs"] == 4 and summary["generated"] == 4 and summary["failed"] == 0
    folders = sorted(p.name for p in cli_out.iterdir() if p.is_dir())
    assert folders == sorted(p.name for p in ray_out.iterdir() if p.is_dir())
    assert len(folders) == 4
    for folder in folders:
        for name in ("scene.json", "scene.glb"):
            assert (ray_out / folder / name).read_bytes() == (cli_out / folder / name).read_bytes(), (folder, name)
    # A rerun finds every job finished.
    again = subprocess.run(
        [sys.executable, str(EXAMPLE), str(prompts), "--out", str(ray_out), "--seeds", "2",
         "--no-preview", "--num-cpus", "2"],
        check=True, capture_output=True, text=True, env=env, timeout=600,
    )
    assert json.loads(again.stdout.strip().splitlines()[-1])["skipped"] == 4
