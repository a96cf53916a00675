"""Type stubs of the native module (PyO3). Use the package's public API instead."""

from typing import Callable, List, Optional, Tuple

__version__: str

class ScenethesisError(Exception):
    """Base class of every error scenethesis raises."""

class InvalidInputError(ScenethesisError):
    """A prompt, plan, setting, file or folder scenethesis cannot use."""

class ProviderError(ScenethesisError):
    """A model provider failed or answered something unusable."""

class SceneRejectedError(ScenethesisError):
    """The judge did not accept the scene and strict=True was asked."""

class Settings:
    def __init__(
        self,
        *,
        planner: str = ...,
        judge: str = ...,
        assets: Optional[str] = ...,
        preview: bool = ...,
        max_replans: int = ...,
        llm_model: Optional[str] = ...,
        vlm_model: Optional[str] = ...,
        image_model: Optional[str] = ...,
        base_url: Optional[str] = ...,
        api_key_env: Optional[str] = ...,
        llm_config: Optional[str] = ...,
        llm_timeout: Optional[float] = ...,
        llm_cache: Optional[str] = ...,
        llm_replay: bool = ...,
        time_limit: Optional[float] = ...,
        open_state: str = ...,
    ) -> None: ...

class NativeScene:
    def scene_json(self) -> str: ...
    def report_json(self) -> Optional[str]: ...
    def accepted(self) -> Optional[bool]: ...
    def summary_line(self) -> Optional[str]: ...
    def rejection_reasons(self) -> str: ...
    def objects_json(self) -> str: ...
    def preview_names(self) -> List[str]: ...
    def preview_rgba(self, name: str, size: Tuple[int, int] = ...) -> Tuple[bytes, int, int]: ...
    def save(self, folder: str, force: bool = ...) -> str: ...
    def export(self, path: str) -> List[str]: ...
    def evaluate(self) -> str: ...

def generate(
    prompt: Optional[str],
    seed: int,
    settings: Settings,
    plan_json: Optional[str] = ...,
    progress: Optional[Callable[[str, str, int, float, str], None]] = ...,
) -> NativeScene: ...
def plan(prompt: str, seed: int, settings: Settings) -> str: ...
def load(folder: str, assets: Optional[str] = ...) -> NativeScene: ...
def evaluate_path(path: str) -> str: ...
def batch_jobs(prompts: List[str], seeds: int = ..., base_seed: int = ...) -> List[Tuple[int, str, int, str]]: ...
