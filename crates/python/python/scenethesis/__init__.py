"""scenethesis: text (or a photo) to interactive, simulation-ready 3D scenes.

The offline default needs no API key, no GPU and no download::

    import scenethesis
    scene = scenethesis.generate("a cozy living room with reading materials", seed=0)
    print(scene.summary)              # the line the CLI prints
    scene.save("out/living_room")     # scene.glb, scene.json, previews, report.json
    scene.export("out/living_room.usda")
    for obj in scene.objects:         # id, category, parent, relations, pose (4x4), bounds
        print(obj.id, obj.category, obj.pose[:3, 3])

The same prompt and seed give byte-identical files from Python and from the ``scenethesis``
command line. Long calls release the GIL, so threads generate in parallel.
"""

from __future__ import annotations

from ._api import (
    Object,
    ProgressEvent,
    Scene,
    batch_jobs,
    evaluate,
    generate,
    load,
    plan,
)
from ._native import (
    InvalidInputError,
    ProviderError,
    SceneRejectedError,
    ScenethesisError,
    __version__,
)

__all__ = [
    "InvalidInputError",
    "Object",
    "ProgressEvent",
    "ProviderError",
    "Scene",
    "SceneRejectedError",
    "ScenethesisError",
    "__version__",
    "batch_jobs",
    "evaluate",
    "generate",
    "load",
    "plan",
]
