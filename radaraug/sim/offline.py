"""Offline generation: simulate a scene into a radaraug HDF5 capture, sharded and resumable.

A scene plays continuously: frame ``k`` starts at ``k * frame_repetition_time`` and the people
walk on from their start positions. Frames are simulated in blocks of ``block_frames``; the
receiver noise of block ``b`` comes from a generator seeded by ``(seed, b)``, so every frame is
a pure function of ``(scene, seed, k)`` however the job is split.

``--shard i/n`` takes the ``i``-th of ``n`` contiguous, block-aligned ranges of frames and writes
``<out stem>.shard-<i>-of-<n>.h5``; a cluster scheduler runs the pieces independently. Re-running
the same command resumes: frames already flushed to the output (the capture format flushes every
append in SWMR mode, so they survive a crash) are kept and simulation continues after them.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug.errors import CaptureError, ConfigError
from radaraug.io import CaptureWriter, open_capture
from radaraug.scene.scene import Scene
from radaraug.sim.seeding import item_generator
from radaraug.sim.twin import DigitalTwin

BLOCK_FRAMES = 16


def parse_shard(text: str | None) -> tuple[int, int]:
    """``"i/n"`` -> ``(i, n)`` with ``0 <= i < n`` (None -> ``(0, 1)``)."""
    if text is None:
        return 0, 1
    try:
        i_str, n_str = text.split("/")
        i, n = int(i_str), int(n_str)
    except ValueError:
        raise ConfigError(f"--shard must look like i/n (e.g. 0/4), got {text!r}") from None
    if n < 1 or not 0 <= i < n:
        raise ConfigError(f"--shard {text}: need n >= 1 and 0 <= i < n")
    return i, n


def shard_range(num_frames: int, shard: tuple[int, int], block: int = BLOCK_FRAMES) -> tuple[int, int]:
    """Frames ``[start, stop)`` of ``shard`` (block-aligned so blocks never straddle shards)."""
    i, n = shard
    blocks = -(-num_frames // block)
    b0, b1 = (blocks * i) // n, (blocks * (i + 1)) // n
    return min(b0 * block, num_frames), min(b1 * block, num_frames)


def shard_path(out: str | os.PathLike, shard: tuple[int, int]) -> Path:
    """Output file of ``shard`` (``out`` itself when there is a single shard)."""
    out = Path(out)
    if shard[1] == 1:
        return out
    return out.with_name(f"{out.stem}.shard-{shard[0]}-of-{shard[1]}{out.suffix or '.h5'}")


def people_inside(twin: DigitalTwin, people: list[Any], times: torch.Tensor) -> np.ndarray:
    """Per frame, how many people have their pelvis inside the room's bounding box."""
    if not people:
        return np.zeros(len(times), dtype=np.int64)
    verts = twin.scene.room.vertices.to(torch.float64)
    lo, hi = verts.min(0).values, verts.max(0).values
    counts = torch.zeros(len(times), dtype=torch.int64)
    for p in people:
        c = p.ellipsoids(times.to(torch.float64)).centers.mean(dim=-2)  # (T, 3) body centre
        inside = ((c[:, :2] >= lo[:2]) & (c[:, :2] <= hi[:2])).all(-1)
        counts += inside.long()
    return counts.numpy()


def simulate_capture(
    scene: Scene | str | os.PathLike,
    out: str | os.PathLike,
    *,
    frames: int,
    seed: int = 0,
    shard: tuple[int, int] = (0, 1),
    device: str = "cpu",
    progress: bool = True,
    twin_options: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Simulate ``frames`` frames of ``scene`` (this shard's part) into a capture file.

    Returns:
        ``{"path", "frames": [start, stop), "resumed_from", "simulated"}``.
    """
    if not isinstance(scene, Scene):
        scene = Scene.from_file(scene)
    if frames < 1:
        raise ConfigError(f"--frames must be >= 1, got {frames}")
    start, stop = shard_range(frames, shard)
    path = shard_path(out, shard)
    attrs = {
        "source": "radaraug simulate",
        "description": f"simulated scene {scene.name!r}",
        "simulation": {"scene": scene.to_dict(), "seed": seed, "frames_total": frames,
                       "shard": list(shard), "first_frame": start, "block_frames": BLOCK_FRAMES},
    }
    done = _existing_frames(path, scene, seed, start)
    if done >= stop - start:
        return {"path": str(path), "frames": [start, stop], "resumed_from": stop, "simulated": 0}
    twin = DigitalTwin(scene, device=device, **(twin_options or {}))
    period = twin.config.frame_repetition_time_s
    path.parent.mkdir(parents=True, exist_ok=True)
    if done:
        writer = CaptureWriter.resume(path, twin.config)
    else:
        writer = CaptureWriter(path, twin.config, labels_schema={"count": "int64", "occupancy": "int64"},
                               attrs=attrs)
    with writer:
        first = start + done
        blocks = range(first // BLOCK_FRAMES, -(-stop // BLOCK_FRAMES))
        if progress:
            from tqdm.auto import tqdm

            blocks = tqdm(blocks, desc=f"simulate {path.name}", unit="block")
        for block_id in blocks:
            # The whole block is simulated even where only part of it is written (a shard edge or
            # a resume point), so a frame is the same whichever run produced it.
            b_start = block_id * BLOCK_FRAMES
            times = torch.arange(b_start, b_start + BLOCK_FRAMES, dtype=torch.float64) * period
            gen = item_generator(seed, block_id, stream=2, device=device)
            counts = twin.receiver.to_counts(twin.simulate(scene.people, times, generators=gen)).cpu()
            inside = people_inside(twin, scene.people, times)
            for k in range(max(b_start, first), min(b_start + BLOCK_FRAMES, stop)):
                j = k - b_start
                writer.append(counts[j].to(torch.int32).numpy().astype(np.uint16), timestamp=float(times[j]),
                              labels={"count": int(inside[j]), "occupancy": int(inside[j] > 0)})
    return {"path": str(path), "frames": [start, stop], "resumed_from": start + done,
            "simulated": stop - start - done}


def _existing_frames(path: Path, scene: Scene, seed: int, start: int) -> int:
    """Frames already in ``path`` from an earlier run of the same job (0 when there is none)."""
    if not path.exists():
        return 0
    try:
        cap = open_capture(path)
    except CaptureError:
        # Broken beyond what SWMR protects (killed before its first flush): start again.
        return 0
    with cap:
        sim = cap.attrs.get("simulation")
        if isinstance(sim, str):
            import json

            sim = json.loads(sim)
        same = isinstance(sim, dict) and sim.get("seed") == seed and sim.get("first_frame") == start \
            and sim.get("scene") == _jsonable(scene.to_dict())
        if not same:
            raise CaptureError(
                f"{path} exists and was not made by this job (other scene, seed or shard); "
                "remove it or choose another output"
            )
        return cap.num_frames


def _jsonable(d: Any) -> Any:
    import json

    return json.loads(json.dumps(d))
