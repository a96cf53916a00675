"""The Pythonic layer over the native module: argument checks, numpy arrays, dataclasses."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._native import SceneRejectedError

PathLike = Union[str, "os.PathLike[str]"]

_PLANNERS = ("knowledge", "llm")
_OPEN_STATES = ("closed", "random", "open")
_JUDGES = ("geometric", "vlm")


class ProgressEvent(NamedTuple):
    """One stage starting or finishing, as passed to a ``progress`` callback."""

    stage: str
    """The stage: plan, retrieve, guide, correspond, optimize, judge, preview or export."""
    event: str
    """``"started"`` or ``"finished"``."""
    round: int
    """0 for the first attempt, k for the k-th re-plan."""
    seconds: float
    """Seconds the stage took (0 when it starts)."""
    note: str
    """What the stage did, as the CLI prints it (empty when it starts)."""


@dataclass(frozen=True)
class Object:
    """One object of a scene."""

    id: str
    """Stable id: the glTF node name and the key in scene.json."""
    category: str
    """Asset category, e.g. ``"sofa"``."""
    parent: str
    """The supporting object's id, a wall id, or ``"ground"``."""
    support: str
    """How it rests on its parent: ``on_floor``, ``on``, ``in``, ``under``, ``mounted``…"""
    relations: List[Tuple[str, str]]
    """Stated relations: (kind, target id)."""
    pose: np.ndarray = field(repr=False)
    """4×4 float64 transform from the asset's frame to the world (+Y up, metres)."""
    bounds: np.ndarray = field(repr=False)
    """2×3 float64 world axis-aligned bounds: ``bounds[0]`` min corner, ``bounds[1]`` max."""
    asset: str
    """The asset reference (procedural generator and seed, or an imported file)."""


def _check_type(name: str, value: Any, types: Any, what: str) -> None:
    if not isinstance(value, types) or (isinstance(value, bool) and bool not in _as_tuple(types)):
        raise TypeError(f"{name} must be {what}, not {type(value).__name__}")


def _as_tuple(types: Any) -> tuple:
    return types if isinstance(types, tuple) else (types,)


def _check_seed(seed: Any) -> int:
    _check_type("seed", seed, int, "an int")
    if not 0 <= seed < 2**64:
        raise ValueError(f"seed must be in [0, 2**64), not {seed}")
    return seed


def _check_prompt(prompt: Any) -> str:
    _check_type("prompt", prompt, str, "a str")
    if not prompt.strip():
        raise ValueError('prompt is empty: describe a scene, e.g. "a cozy living room"')
    return prompt


def _optional_path(name: str, value: Any) -> Optional[str]:
    if value is None:
        return None
    _check_type(name, value, (str, os.PathLike), "a str or path")
    return os.fspath(value)


def _optional_str(name: str, value: Any) -> Optional[str]:
    if value is not None:
        _check_type(name, value, str, "a str")
    return value


def _settings(
    planner: str,
    judge: str,
    assets: Optional[PathLike],
    preview: bool,
    max_replans: int,
    llm_model: Optional[str],
    vlm_model: Optional[str],
    image_model: Optional[str],
    base_url: Optional[str],
    api_key_env: Optional[str],
    llm_config: Optional[PathLike],
    llm_timeout: Optional[float],
    llm_cache: Optional[PathLike],
    llm_replay: bool,
    time_limit: Optional[float] = None,
    open_state: str = "closed",
) -> "_native.Settings":
    _check_type("planner", planner, str, "a str")
    if planner not in _PLANNERS:
        raise ValueError(f"planner must be one of {', '.join(_PLANNERS)}, not {planner!r}")
    _check_type("judge", judge, str, "a str")
    if judge not in _JUDGES:
        raise ValueError(f"judge must be one of {', '.join(_JUDGES)}, not {judge!r}")
    _check_type("preview", preview, bool, "a bool")
    _check_type("max_replans", max_replans, int, "an int")
    if not 0 <= max_replans <= 100:
        raise ValueError(f"max_replans must be in [0, 100], not {max_replans}")
    if llm_timeout is not None:
        _check_type("llm_timeout", llm_timeout, (int, float), "a number of seconds")
        if not 0 < llm_timeout < 86400:
            raise ValueError(f"llm_timeout must be in (0, 86400) seconds, not {llm_timeout}")
    _check_type("llm_replay", llm_replay, bool, "a bool")
    if llm_replay and llm_cache is None:
        raise ValueError("llm_replay=True needs llm_cache, the folder to replay from")
    if time_limit is not None:
        _check_type("time_limit", time_limit, (int, float), "a number of seconds")
    _check_type("open_state", open_state, str, "a str")
    if open_state not in _OPEN_STATES:
        raise ValueError(
            f"open_state must be one of {', '.join(_OPEN_STATES)}, not {open_state!r}"
        )
    return _native.Settings(
        planner=planner,
        judge=judge,
        assets=_optional_path("assets", assets),
        preview=preview,
        max_replans=max_replans,
        llm_model=_optional_str("llm_model", llm_model),
        vlm_model=_optional_str("vlm_model", vlm_model),
        image_model=_optional_str("image_model", image_model),
        base_url=_optional_str("base_url", base_url),
        api_key_env=_optional_str("api_key_env", api_key_env),
        llm_config=_optional_path("llm_config", llm_config),
        llm_timeout=None if llm_timeout is None else float(llm_timeout),
        llm_cache=_optional_path("llm_cache", llm_cache),
        llm_replay=llm_replay,
        time_limit=None if time_limit is None else float(time_limit),
        open_state=open_state,
    )


class Scene:
    """A generated or loaded scene: its graph, objects, report and previews.

    Made by :func:`generate` or :func:`load`, never directly.
    """

    __slots__ = ("_native", "_objects", "_report")

    def __init__(self, native: "_native.NativeScene") -> None:
        self._native = native
        self._objects: Optional[List[Object]] = None
        self._report: Optional[Dict[str, Any]] = None

    @property
    def prompt(self) -> str:
        """The prompt the scene was made from."""
        return str(self.to_dict()["prompt"])

    @property
    def seed(self) -> int:
        """The seed the scene was made with."""
        return int(self.to_dict()["seed"])

    @property
    def accepted(self) -> Optional[bool]:
        """Whether the judge accepted the scene (``None`` for a loaded scene without report)."""
        return self._native.accepted()

    @property
    def summary(self) -> Optional[str]:
        """The report's one-line summary, as the CLI prints it."""
        return self._native.summary_line()

    @property
    def objects(self) -> List[Object]:
        """Every object, in scene.json order (parents before children)."""
        if self._objects is None:
            self._objects = [
                Object(
                    id=o["id"],
                    category=o["category"],
                    parent=o["parent"],
                    support=o["support"],
                    relations=[(k, t) for k, t in o["relations"]],
                    pose=np.asarray(o["pose"], dtype=np.float64).reshape(4, 4),
                    bounds=np.asarray(o["bounds"], dtype=np.float64).reshape(2, 3),
                    asset=o["asset"],
                )
                for o in json.loads(self._native.objects_json())
            ]
        return list(self._objects)

    def object(self, id: str) -> Object:
        """The object called ``id`` (``KeyError`` when there is none)."""
        for o in self.objects:
            if o.id == id:
                return o
        raise KeyError(id)

    @property
    def report(self) -> Optional[Dict[str, Any]]:
        """The content of report.json: metrics, verdict, re-plans, timings (``None`` for a
        loaded folder without one)."""
        if self._report is None:
            text = self._native.report_json()
            self._report = None if text is None else json.loads(text)
        return None if self._report is None else dict(self._report)

    def to_dict(self) -> Dict[str, Any]:
        """The scene graph: the content of scene.json."""
        return json.loads(self._native.scene_json())

    def save(self, folder: PathLike, *, force: bool = False) -> str:
        """Writes the output folder as ``scenethesis generate --out`` does: scene.glb,
        scene.json, the previews and report.json, atomically. An existing folder is replaced
        only when it holds an earlier scenethesis output (anything else needs ``force=True``).
        Returns the absolute path written."""
        path = _optional_path("folder", folder)
        if path is None:
            raise TypeError("folder must be a str or path, not None")
        _check_type("force", force, bool, "a bool")
        return self._native.save(path, force)

    def export(self, path: PathLike) -> List[str]:
        """Writes the scene to ``path`` in the format its suffix names: ``.glb`` (glTF),
        ``.usda`` (OpenUSD), ``.xml`` (MuJoCo MJCF) or ``.urdf`` (meshes go to
        ``<stem>_meshes/`` beside it). Returns the files written."""
        target = _optional_path("path", path)
        if target is None:
            raise TypeError("path must be a str or path, not None")
        if os.path.splitext(target)[1].lower() not in (".glb", ".usda", ".usd", ".xml", ".urdf"):
            raise ValueError(
                f"path must end in .glb, .usda, .xml (MJCF) or .urdf, not {os.path.basename(target)!r}"
            )
        return self._native.export(target)

    @property
    def preview_names(self) -> List[str]:
        """The preview images the scene holds (e.g. ``preview.png``, ``preview_top.png``)."""
        return self._native.preview_names()

    def preview(self, name: str = "preview.png", *, size: Tuple[int, int] = (1024, 768)) -> np.ndarray:
        """A preview image as an ``(height, width, 4)`` uint8 RGBA array. A scene generated
        with ``preview=False`` (or a folder without previews) is rendered now at ``size``
        (``preview.png`` the photo view, ``preview_top.png`` from above); that needs a GPU or
        Mesa's software renderer."""
        _check_type("name", name, str, "a str")
        if (
            not isinstance(size, (tuple, list))
            or len(size) != 2
            or not all(isinstance(v, int) and not isinstance(v, bool) for v in size)
        ):
            raise TypeError("size must be a (width, height) pair of ints")
        if not all(16 <= v <= 8192 for v in size):
            raise ValueError(f"size must be within 16..8192 pixels per side, not {tuple(size)}")
        data, width, height = self._native.preview_rgba(name, (size[0], size[1]))
        return np.frombuffer(data, dtype=np.uint8).reshape(height, width, 4).copy()

    def evaluate(self) -> Dict[str, Any]:
        """The metrics of ``scenethesis eval --json`` for this scene."""
        return json.loads(self._native.evaluate())

    def __repr__(self) -> str:
        return f"<scenethesis.Scene {self.prompt!r} seed={self.seed} objects={len(self.objects)} accepted={self.accepted}>"


def _plan_json(plan: Any) -> str:
    if isinstance(plan, Mapping):
        return json.dumps(plan)
    if isinstance(plan, (str, os.PathLike)):
        with open(os.fspath(plan), encoding="utf-8") as f:
            return f.read()
    raise TypeError(f"plan must be a dict or the path of a plan.json, not {type(plan).__name__}")


def generate(
    prompt: Optional[str] = None,
    seed: int = 0,
    *,
    plan: Optional[Union[Mapping[str, Any], PathLike]] = None,
    planner: str = "knowledge",
    judge: str = "geometric",
    assets: Optional[PathLike] = None,
    preview: bool = True,
    max_replans: int = 3,
    strict: bool = False,
    llm_model: Optional[str] = None,
    vlm_model: Optional[str] = None,
    image_model: Optional[str] = None,
    base_url: Optional[str] = None,
    api_key_env: Optional[str] = None,
    llm_config: Optional[PathLike] = None,
    llm_timeout: Optional[float] = None,
    llm_cache: Optional[PathLike] = None,
    llm_replay: bool = False,
    time_limit: Optional[float] = 600.0,
    progress: Optional[Callable[[ProgressEvent], None]] = None,
    open_state: str = "closed",
) -> Scene:
    """Generates a simulation-ready scene: plan → retrieve → guide → optimize → judge, re-planning
    while the judge rejects it (``scenethesis generate``).

    Give a ``prompt``, or a ``plan`` (a dict from :func:`plan`, or a plan.json path) to build
    from. ``planner="llm"`` / ``judge="vlm"`` use an OpenAI-compatible server (``base_url``,
    ``llm_model``, ``vlm_model``, the key from ``$OPENAI_API_KEY`` or ``api_key_env``;
    ``llm_cache`` records answers and ``llm_replay=True`` replays them offline). ``assets``
    is a folder of your own GLB/glTF/OBJ files. ``progress`` is called with a
    :class:`ProgressEvent` as each stage starts and finishes; an exception it raises ends the
    run before the next stage and is raised from here, as is ``KeyboardInterrupt`` when Ctrl-C
    is pressed during a run on the main thread. ``time_limit`` is the run's
    budget in seconds (``None`` or 0 for none), checked before every stage: once spent, the best
    scene so far is returned (its report's notes say so), or the run raises if it has none.
    ``open_state`` leaves doors, drawers and lids ``"closed"``, at ``"random"`` states fixed by
    the seed, or ``"open"`` (90 % of each joint's range, which the judge keeps free), as
    ``--open-state`` does.

    A scene the judge rejects is returned (``scene.accepted`` is False, with a warning)
    unless ``strict=True``, which raises :class:`SceneRejectedError` carrying it as ``.scene``.

    Raises :class:`InvalidInputError` for an unusable prompt, plan, setting or folder,
    :class:`ProviderError` when a model server fails, ``TypeError``/``ValueError`` for a wrong
    argument (named in the message).
    """
    if plan is not None and prompt is not None:
        raise ValueError("give prompt or plan, not both (the plan holds its prompt)")
    if plan is None:
        if prompt is None:
            raise TypeError("generate() needs a prompt (or plan=...)")
        prompt = _check_prompt(prompt)
    seed = _check_seed(seed)
    _check_type("strict", strict, bool, "a bool")
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable, not {type(progress).__name__}")
    settings = _settings(
        planner, judge, assets, preview, max_replans, llm_model, vlm_model, image_model,
        base_url, api_key_env, llm_config, llm_timeout, llm_cache, llm_replay, time_limit,
        open_state,
    )
    callback = None
    if progress is not None:
        user = progress

        def callback(stage: str, event: str, round: int, seconds: float, note: str) -> None:
            user(ProgressEvent(stage, event, round, seconds, note))

    native = _native.generate(
        prompt, seed, settings, None if plan is None else _plan_json(plan), callback
    )
    scene = Scene(native)
    if scene.accepted is False:
        reasons = native.rejection_reasons()
        if strict:
            err = SceneRejectedError(f"the judge did not accept the scene: {reasons}")
            err.scene = scene  # type: ignore[attr-defined]
            raise err
        import warnings

        warnings.warn(f"the judge did not accept the scene: {reasons}", stacklevel=2)
    return scene


def plan(
    prompt: str,
    seed: int = 0,
    *,
    planner: str = "knowledge",
    assets: Optional[PathLike] = None,
    llm_model: Optional[str] = None,
    base_url: Optional[str] = None,
    api_key_env: Optional[str] = None,
    llm_config: Optional[PathLike] = None,
    llm_timeout: Optional[float] = None,
    llm_cache: Optional[PathLike] = None,
    llm_replay: bool = False,
) -> Dict[str, Any]:
    """The editable plan for ``prompt`` (``scenethesis plan``): objects, anchor, supports,
    relations, room. Edit it and pass it to ``generate(plan=...)``."""
    prompt = _check_prompt(prompt)
    seed = _check_seed(seed)
    settings = _settings(
        planner, "geometric", assets, False, 0, llm_model, None, None, base_url, api_key_env,
        llm_config, llm_timeout, llm_cache, llm_replay,
    )
    return json.loads(_native.plan(prompt, seed, settings))


def load(folder: PathLike, *, assets: Optional[PathLike] = None) -> Scene:
    """Reads an output folder of ``generate`` (scene.json, report.json, previews). Imported
    assets are re-read from the paths in scene.json, or from ``assets`` if the folder moved."""
    path = _optional_path("folder", folder)
    if path is None:
        raise TypeError("folder must be a str or path, not None")
    return Scene(_native.load(path, _optional_path("assets", assets)))


def evaluate(scene_or_folder: Union[Scene, PathLike]) -> Dict[str, Any]:
    """The metrics of ``scenethesis eval --json``: collisions (Col-O, Col-S), stability
    (Inst-O, Inst-S), Walk, Reach and content, for a :class:`Scene`, an output folder, a
    scene.json or any .glb scene."""
    if isinstance(scene_or_folder, Scene):
        return scene_or_folder.evaluate()
    path = _optional_path("scene_or_folder", scene_or_folder)
    if path is None:
        raise TypeError("scene_or_folder must be a Scene, a str or a path, not None")
    return json.loads(_native.evaluate_path(path))


def batch_jobs(prompts: Sequence[str], seeds: int = 1, base_seed: int = 0) -> List[Tuple[int, str, int, str]]:
    """The jobs ``scenethesis batch`` makes of ``prompts`` × ``seeds`` seeds from
    ``base_seed``, in its order: ``(position, prompt, seed, folder)``. Writing job ``j``'s
    ``generate(prompt, seed, preview=...)`` to ``out/folder`` gives the CLI batch's folder."""
    if isinstance(prompts, str) or not all(isinstance(p, str) for p in prompts):
        raise TypeError("prompts must be a sequence of str")
    _check_type("seeds", seeds, int, "an int")
    if seeds < 1:
        raise ValueError(f"seeds must be at least 1, not {seeds}")
    base_seed = _check_seed(base_seed)
    return _native.batch_jobs(list(prompts), seeds, base_seed)
