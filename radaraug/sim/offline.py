"""Offline generation: simulate a scene into a radaraug HDF5 capture, sharded and resumable.

The scene plays continuously; the receiver noise of frame block ``b`` comes from ``(seed, b)``, so a
frame is a pure function of ``(scene, seed, k)`` and the device type however the job is split.
Re-running a job resumes it; a file of another job is refused. See docs/simulation.md ("Offline
generation").
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import torch

from radaraug._optional import lazy_import
from radaraug._torch import parse_device
from radaraug.errors import CaptureError, ConfigError
from radaraug.files import parse_json
from radaraug.io import hdf5_format as fmt
from radaraug.io import open_capture
from radaraug.io.blocks import BLOCK_FRAMES, BlockWriter, blocks_covering, frame_times
from radaraug.io.hdf5_recovery import status_flags, writer_is_alive
from radaraug.io.hdf5_writer import check_free_space
from radaraug.scene.scene import Scene
from radaraug.sensor.profile import as_profile
from radaraug.sim.seeding import Stream, item_generator
from radaraug.sim.twin import DigitalTwin


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


def people_inside(twin: DigitalTwin, people: list[Any], times: torch.Tensor, *,
                  min_range_m: float | None = None) -> np.ndarray:
    """Per frame, how many people have their pelvis inside the room's bounding box.

    With ``min_range_m``, only those also at least that far in front of the radar along its
    horizontal boresight count (the proxy's label rule, :func:`radaraug.testsets.proxy.people_in_view`).
    """
    counts = np.zeros(len(times), dtype=np.int64)
    verts = twin.scene.room.vertices.to(torch.float64)
    lo, hi = verts.min(0).values, verts.max(0).values
    pose = twin.scene.radar
    axis = pose.rotation[:, 2].to(torch.float64).clone()
    axis[2] = 0.0
    axis = axis / axis.norm()
    for p in people:
        c = p.ellipsoids(times.to(torch.float64)).centers.mean(dim=-2)  # (T, 3) body centre
        inside = ((c[:, :2] >= lo[:2]) & (c[:, :2] <= hi[:2])).all(-1).numpy()
        if min_range_m is not None:
            inside &= ((c - pose.position.to(torch.float64))[:, :2] @ axis[:2]).numpy() >= min_range_m
        counts += inside
    return counts


def simulate_frames(twin: DigitalTwin, people: list[Any], start: int, stop: int, seed: int, block: int,
                    device: str | torch.device, **options: Any) -> tuple[torch.Tensor, torch.Tensor]:
    """``(times, frames)``: frames ``[start, stop)`` of ``people`` simulated by ``twin``.

    Receiver noise from ``(seed, block)`` (``Stream.BLOCK_NOISE``, shared with the virtual sensor and
    the proxy); ``options`` go to :meth:`DigitalTwin.simulate`.
    """
    times = frame_times(start, stop, twin.config.frame_repetition_time_s)
    gen = item_generator(seed, block, stream=Stream.BLOCK_NOISE, device=device)
    return times, twin.simulate(people, times, generators=gen, **options)


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
    profile: Any = None,
) -> dict[str, Any]:
    """Simulate ``frames`` frames of ``scene`` (this shard's part) into a capture file.

    Args:
        scene: a :class:`Scene`, a scene file or a built-in scene name.
        out: output capture (``out`` itself, or ``<stem>.shard-<i>-of-<n>.h5`` for a shard).
        frames: total frames of the whole job (all shards).
        seed: noise seed; frame ``k`` depends only on ``(scene, seed, k)`` and the device type.
        shard: ``(i, n)``: this run simulates the ``i``-th of ``n`` block-aligned pieces.
        device: where to simulate.
        progress: show a progress bar.
        twin_options: keyword arguments of :class:`DigitalTwin`.
        profile: a fitted twin profile (object, JSON path or dict) for the receiver; part of the
            job's identity.

    Returns:
        ``{"path", "frames": [start, stop), "resumed_from", "simulated"}``.

    Raises:
        SceneError: bad scene.
        ConfigError: ``frames < 1`` or a bad shard or device.
        CaptureError: ``out`` exists and was not written by this same job, another process has it
            open, it cannot be created, there is not enough space, or the disk fills up while
            writing (the file keeps every completed frame; a re-run resumes it).
    """
    scene = Scene.load(scene)
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise ConfigError(f"--frames must be an integer >= 1, got {frames!r}")
    if parse_shard(f"{shard[0]}/{shard[1]}") != tuple(shard):  # validates (i, n) given from Python
        raise ConfigError(f"shard must be (i, n) with 0 <= i < n, got {shard!r}")
    device_type = parse_device(device).type
    start, stop = shard_range(frames, shard)
    path = shard_path(out, shard)
    job = {"scene": _jsonable(scene.to_dict()), "seed": seed, "frames_total": frames, "shard": list(shard),
           "first_frame": start, "block_frames": BLOCK_FRAMES, "device_type": device_type}
    prof = as_profile(profile)
    if prof is not None:
        job["profile"] = prof.to_dict()["receiver"]
        if prof.room:
            job["profile_room"] = dict(prof.room)  # only when present: older jobs keep their identity
        twin_options = {**(twin_options or {}), "profile": prof}
    attrs = {
        "source": "radaraug simulate",
        "description": f"simulated scene {scene.name!r}",
        "simulation": job,
    }
    done = _existing_frames(path, job)
    if done > stop - start:
        raise CaptureError(f"{path} holds {done} frames, more than this job's {stop - start}; remove it")
    if done == stop - start:
        return {"path": str(path), "frames": [start, stop], "resumed_from": stop, "simulated": 0}
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise CaptureError(f"{path}: cannot create its folder {path.parent} ({e.strerror or e})") from None
    todo = stop - start - done
    # Before the twin is built (tracing the room takes a while): refuse what cannot fit.
    config = (twin_options or {}).get("config") or scene.config
    check_free_space(path, config, todo, existing=path.stat().st_size if done else 0)
    twin = DigitalTwin(scene, device=device, **(twin_options or {}))
    if done:
        writer = BlockWriter.resume(path, twin.config, expected_frames=todo)
    else:
        writer = BlockWriter.create(path, twin.config, attrs=attrs, expected_frames=todo)
    with writer:
        first = start + done
        blocks = blocks_covering(first, stop)
        if progress:
            tqdm = lazy_import("tqdm.auto", feature="progress bars").tqdm

            blocks = tqdm(blocks, desc=f"simulate {path.name}", unit="block")
        for block_id in blocks:
            # The whole block is simulated even where only part of it is written (a shard edge or
            # a resume point), so a frame is the same whichever run produced it.
            b0 = block_id * BLOCK_FRAMES
            times, x = simulate_frames(twin, scene.people, b0, b0 + BLOCK_FRAMES, seed, block_id, device)
            counts = twin.receiver.to_counts(x).cpu()
            inside = people_inside(twin, scene.people, times)
            lo, hi = max(b0, first) - b0, min(b0 + BLOCK_FRAMES, stop) - b0
            writer.write(counts[lo:hi], times[lo:hi], inside[lo:hi])
    return {"path": str(path), "frames": [start, stop], "resumed_from": start + done,
            "simulated": stop - start - done}


def _existing_frames(path: Path, job: dict[str, Any]) -> int:
    """Frames already in ``path`` from an earlier run of the same ``job`` (0 when there is none).

    Raises:
        CaptureError: ``path`` is something else (another job's capture, or not ours at all).
    """
    if not path.exists() and not path.is_symlink():
        return 0
    refuse = CaptureError(
        f"{path} exists and was not made by this job (other scene, seed, frame count, shard or device "
        "type, or not a simulated capture); remove it or choose another output"
    )
    if not path.is_file():
        raise refuse
    if writer_is_alive(path):
        raise CaptureError(f"{path}: another process has this file open (a writer, or a reader: HDF5 readers lock files too); wait for it, close it or choose another output")
    if fmt.looks_like_hdf5(path):
        # Check the superblock (checksum, length) before HDF5 opens the file: a damaged file is not
        # ours (the writer only ever gives its name to a file that opens), and HDF5 can hang for a
        # long time on damaged metadata.
        try:
            status_flags(path)
        except CaptureError as e:
            raise CaptureError(f"{refuse} [{e}]") from None
        if fmt.stored_eof_shortfall(path):
            raise CaptureError(f"{refuse} [it is a truncated HDF5 file]")
    try:
        with open_capture(path) as cap:
            sim, done = cap.attrs.get("simulation"), cap.num_frames
    except CaptureError:
        # A run killed before its first complete frame holds no frame yet: it starts again;
        # anything else that does not open is not ours to overwrite.
        sim, done = _raw_simulation_attr(path), 0
        if sim is _BROKEN_HDF5:
            raise refuse from None
    if isinstance(sim, (str, bytes)):
        try:
            sim = parse_json(sim, source=path, error=CaptureError, what="attribute 'simulation'")
        except CaptureError:
            raise refuse from None
    if not isinstance(sim, dict):
        raise refuse
    sim = {"device_type": "cpu", **sim}  # files written before the device type was recorded
    if any(sim.get(k) != v for k, v in job.items()):
        raise refuse
    return done


_BROKEN_HDF5 = object()


def _raw_simulation_attr(path: Path) -> Any:
    """The ``simulation`` attribute read with h5py alone; None when there is none.

    :data:`_BROKEN_HDF5` for an HDF5 file h5py cannot open. The superblock was checked by the caller.
    """
    import h5py

    if not fmt.looks_like_hdf5(path):
        return None
    # A killed SWMR writer leaves the SWMR-write flag (bit 2): only SWMR reading opens such a file.
    swmr = bool(status_flags(path) & 0x04)
    try:
        with h5py.File(path, "r", swmr=swmr) as f:
            return f.attrs.get("simulation")
    except (OSError, RuntimeError):
        return _BROKEN_HDF5


def _jsonable(d: Any) -> Any:
    import json

    return json.loads(json.dumps(d))
