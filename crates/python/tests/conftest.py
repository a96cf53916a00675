"""Shared fixtures: one offline scene generated once per session, and the CLI binary the
byte-identity tests compare against."""

from __future__ import annotations

import os
import pathlib
import shutil

import pytest

import scenethesis

REPO = pathlib.Path(__file__).resolve().parents[3]
PROMPT = "a small office with a desk and a chair"


def cli_binary() -> pathlib.Path:
    """The `scenethesis` CLI: $SCENETHESIS_CLI, else the workspace's debug or release build.
    With $SCENETHESIS_CLI set (as CI does) a missing binary fails instead of skipping."""
    named = os.environ.get("SCENETHESIS_CLI")
    if named:
        path = pathlib.Path(named)
        assert path.is_file(), f"SCENETHESIS_CLI={named} does not exist"
        return path
    for profile in ("debug", "release"):
        path = REPO / "target" / profile / "scenethesis"
        if path.is_file():
            return path
    found = shutil.which("scenethesis")
    if found:
        return pathlib.Path(found)
    pytest.skip("no scenethesis CLI binary (set SCENETHESIS_CLI)")


@pytest.fixture(scope="session")
def office() -> scenethesis.Scene:
    """An offline scene without previews, generated once."""
    return scenethesis.generate(PROMPT, seed=1, preview=False)


@pytest.fixture(scope="session")
def office_folder(office: scenethesis.Scene, tmp_path_factory: pytest.TempPathFactory) -> pathlib.Path:
    """The office saved as an output folder."""
    folder = tmp_path_factory.mktemp("saved") / "office"
    office.save(folder)
    return folder
