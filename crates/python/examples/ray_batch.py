"""Fan a prompts file out over a Ray cluster through the scenethesis Python API.

Each (prompt, seed) job of ``scenethesis batch`` becomes one Ray task that generates the scene
and saves it into the same sub-folder the CLI batch would write, with the same bytes, so the
CLI and Ray can even share one output folder. Finished folders (a report.json of the same
prompt and seed) are skipped, so a rerun resumes.

    python crates/python/examples/ray_batch.py prompts.txt --out out/ray --seeds 2
    # on a cluster: RAY_ADDRESS=ray://head:10001 python ray_batch.py prompts.txt --out /shared/out

Without RAY_ADDRESS a local Ray instance is started with ``--num-cpus`` CPUs.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from typing import Dict, List

import ray

import scenethesis


def read_prompts(path: str) -> List[str]:
    """The prompts of a prompts file, as ``scenethesis batch`` reads them: one per line, blank
    lines and ``#`` comments skipped."""
    with open(path, encoding="utf-8") as f:
        lines = [line.strip() for line in f]
    return [line for line in lines if line and not line.startswith("#")]


def finished(folder: str, prompt: str, seed: int) -> bool:
    """Whether ``folder`` already holds this job's scene."""
    try:
        with open(os.path.join(folder, "report.json"), encoding="utf-8") as f:
            report = json.load(f)
    except (OSError, ValueError):
        return False
    return report.get("prompt") == prompt and report.get("seed") == seed


@ray.remote(num_cpus=1)
def generate_one(prompt: str, seed: int, folder: str, preview: bool) -> Dict[str, object]:
    """One job: generate, save, and report what happened."""
    started = time.monotonic()
    try:
        scene = scenethesis.generate(prompt, seed, preview=preview)
        scene.save(folder)
    except scenethesis.ScenethesisError as e:
        return {"folder": folder, "status": "failed", "error": str(e)}
    return {
        "folder": folder,
        "status": "generated",
        "accepted": scene.accepted,
        "objects": len(scene.objects),
        "seconds": round(time.monotonic() - started, 3),
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("prompts", help="a text file, one prompt per line")
    parser.add_argument("--out", required=True, help="output folder (one sub-folder per job)")
    parser.add_argument("--seeds", type=int, default=1, help="seeds per prompt")
    parser.add_argument("--seed", type=int, default=0, help="the first seed")
    parser.add_argument("--no-preview", action="store_true", help="do not render previews")
    parser.add_argument("--num-cpus", type=int, default=None, help="CPUs of a local Ray instance")
    args = parser.parse_args()

    jobs = scenethesis.batch_jobs(read_prompts(args.prompts), args.seeds, args.seed)
    os.makedirs(args.out, exist_ok=True)
    if "RAY_ADDRESS" in os.environ:
        ray.init()
    else:
        ray.init(num_cpus=args.num_cpus, include_dashboard=False, log_to_driver=False)
    futures = []
    results: List[Dict[str, object]] = []
    for _, prompt, seed, name in jobs:
        folder = os.path.join(args.out, name)
        if finished(folder, prompt, seed):
            results.append({"folder": folder, "status": "skipped"})
            continue
        futures.append(generate_one.remote(prompt, seed, folder, not args.no_preview))
    started = time.monotonic()
    results.extend(ray.get(futures))
    wall = time.monotonic() - started
    ray.shutdown()
    generated = [r for r in results if r["status"] == "generated"]
    failed = [r for r in results if r["status"] == "failed"]
    for r in failed:
        print(f"FAIL {r['folder']}: {r['error']}", file=sys.stderr)
    per_hour = len(generated) / wall * 3600 if generated and wall > 0 else 0.0
    print(
        json.dumps(
            {
                "jobs": len(jobs),
                "generated": len(generated),
                "skipped": len(results) - len(generated) - len(failed),
                "failed": len(failed),
                "accepted": sum(1 for r in generated if r.get("accepted")),
                "wall_seconds": round(wall, 3),
                "scenes_per_hour": round(per_hour, 1),
            }
        )
    )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
