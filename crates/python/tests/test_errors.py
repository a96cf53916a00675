"""Bad arguments, bad input and failing providers raise the right exception with a clear message."""

from __future__ import annotations

import http.server
import json
import os
import pathlib
import threading
from typing import Iterator

import pytest

import scenethesis


@pytest.mark.parametrize(
    "kwargs, error, text",
    [
        (dict(prompt=""), ValueError, "prompt is empty"),
        (dict(prompt=3), TypeError, "prompt must be a str"),
        (dict(prompt="a kitchen", seed="1"), TypeError, "seed must be an int"),
        (dict(prompt="a kitchen", seed=-1), ValueError, "seed must be in"),
        (dict(prompt="a kitchen", seed=True), TypeError, "seed must be an int"),
        (dict(prompt="a kitchen", planner="gpt"), ValueError, "planner must be one of"),
        (dict(prompt="a kitchen", judge="human"), ValueError, "judge must be one of"),
        (dict(prompt="a kitchen", preview="yes"), TypeError, "preview must be a bool"),
        (dict(prompt="a kitchen", max_replans=-2), ValueError, "max_replans must be in"),
        (dict(prompt="a kitchen", llm_timeout=0), ValueError, "llm_timeout must be in"),
        (dict(prompt="a kitchen", llm_replay=True), ValueError, "needs llm_cache"),
        (dict(prompt="a kitchen", open_state="ajar"), ValueError, "open_state must be one of"),
        (dict(prompt="a kitchen", time_limit="1"), TypeError, "time_limit must be a number"),
        (dict(prompt="a kitchen", time_limit=-1.0), ValueError, "time_limit: expected seconds"),
        (dict(prompt="a kitchen", time_limit=float("nan")), ValueError, "time_limit: expected"),
        (dict(prompt="a kitchen", assets=42), TypeError, "assets must be a str or path"),
        (dict(prompt="a kitchen", progress=5), TypeError, "progress must be callable"),
        (dict(), TypeError, "needs a prompt"),
        (dict(prompt="a kitchen", plan={}), ValueError, "not both"),
    ],
)
def test_bad_arguments_name_the_argument(kwargs: dict, error: type, text: str) -> None:
    with pytest.raises(error, match=text):
        scenethesis.generate(**kwargs)


def test_bad_input_raises_invalid_input(tmp_path: pathlib.Path) -> None:
    with pytest.raises(scenethesis.InvalidInputError) as info:
        scenethesis.generate(plan={"prompt": "x", "objects": "many"}, preview=False)
    assert "plan" in str(info.value)
    with pytest.raises(scenethesis.InvalidInputError, match="scene.json"):
        scenethesis.load(tmp_path / "nowhere")
    with pytest.raises(scenethesis.InvalidInputError, match="importing assets"):
        scenethesis.generate("a kitchen", preview=False, assets=tmp_path / "no_assets_here")
    assert issubclass(scenethesis.InvalidInputError, scenethesis.ScenethesisError)


def test_a_run_out_of_time_raises_naming_the_limit() -> None:
    with pytest.raises(scenethesis.ScenethesisError, match="time limit of 0.000001 s"):
        scenethesis.generate("a kitchen", preview=False, time_limit=1e-6)


def test_save_never_replaces_a_foreign_folder(office: scenethesis.Scene, tmp_path: pathlib.Path) -> None:
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "thesis.tex").write_text("precious")
    with pytest.raises(scenethesis.InvalidInputError, match="thesis.tex"):
        office.save(foreign)
    assert (foreign / "thesis.tex").read_text() == "precious"
    assert not (foreign / "scene.json").exists()
    office.save(foreign, force=True)
    assert (foreign / "scene.json").is_file()


SECRET = "sk-test-0123456789abcdefSECRET"


class EchoingServer(http.server.BaseHTTPRequestHandler):
    """An OpenAI-compatible endpoint that fails every request and echoes the key it was sent."""

    def do_POST(self) -> None:  # noqa: N802 (http.server's naming)
        length = int(self.headers.get("Content-Length", 0))
        self.rfile.read(length)
        body = json.dumps({"error": {"message": f"invalid key {self.headers.get('Authorization')}"}})
        self.send_response(401)
        self.send_header("Content-Type", "application/json")
        self.send_header("Content-Length", str(len(body)))
        self.end_headers()
        self.wfile.write(body.encode())

    def log_message(self, *args: object) -> None:
        pass


@pytest.fixture
def failing_server() -> Iterator[str]:
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), EchoingServer)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    yield f"http://127.0.0.1:{server.server_address[1]}/v1"
    server.shutdown()


def test_a_failing_server_raises_provider_error_without_the_key(
    failing_server: str, tmp_path: pathlib.Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv("SCENETHESIS_TEST_KEY", SECRET)
    config = tmp_path / "llm.toml"
    config.write_text("max_attempts = 1\nbackoff_ms = 0\n")
    with pytest.raises(scenethesis.ProviderError) as info:
        scenethesis.generate(
            "a pharmacy",
            planner="llm",
            base_url=failing_server,
            llm_model="tiny",
            api_key_env="SCENETHESIS_TEST_KEY",
            llm_config=config,
            preview=False,
        )
    message = str(info.value)
    assert "127.0.0.1" in message and "401" in message, message
    assert SECRET not in message and "0123456789abcdef" not in message, message


def test_a_missing_key_variable_is_named(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("SCENETHESIS_NO_SUCH_KEY", raising=False)
    with pytest.raises(scenethesis.InvalidInputError, match="SCENETHESIS_NO_SUCH_KEY"):
        scenethesis.generate("a pharmacy", planner="llm", api_key_env="SCENETHESIS_NO_SUCH_KEY", preview=False)
