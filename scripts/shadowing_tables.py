"""The in-frame shadow table of docs/shadowing.md ("Inside a frame"), measured with the current code.

A thin rod (0.6 m) turning at 6 rad/s 2.6 m out (:class:`radaraug.sim.figures.TurningRod`, 6 frames
0.14 s apart) and the limbs check's walker (``Walker(start=(2.0, 0.3), heading_rad=0.0)``, 4 frames
over 1.1 s) in the built-in corridor, ideal receiver, no multipath, float64: the twin with its shadow
held for the frame (``shadow_intervals=0``) or moved inside it (``K = 1, 2, 4``) against 64 one-chirp
frames each traced at its own chirp's time (:func:`radaraug.sim.figures.traced_at_every_chirp`). The
last column, "none", turns the shadowing off in both the twin and the reference.

- rod: RMS difference (dB) of the Doppler profiles over the bins within 30 dB of the reference's peak.
- walker: per frame, the largest power of the difference's Doppler profile off zero Doppler, dB under
  the reference profile's peak.

Deterministic (no random draws). Command::

    python scripts/shadowing_tables.py -o benchmarks/shadowing_tables_cpu.json
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import Any

import torch

from radaraug.scene.people import Walker
from radaraug.scene.scene import Scene
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.figures import TurningRod, doppler_profiles_db, rod_frame_times
from radaraug.sim.twin import DigitalTwin
from radaraug.transforms import RangeDoppler

COMMAND = "python scripts/shadowing_tables.py -o benchmarks/shadowing_tables_cpu.json"
INTERVALS = (0, 1, 2, 4)
ROD_FRAMES = 6
WALKER_FRAMES = 4


def ideal_twin(scene: Scene, **options: Any) -> DigitalTwin:
    """A float64 twin of ``scene`` with an ideal receiver and no multipath.

    Args:
        scene: the room.
        **options: further :class:`DigitalTwin` options (``shadowing``, ``shadow_intervals``, ...).

    Returns:
        The twin.
    """
    return DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=[]), multipath=False,
                       dtype=torch.float64, **options)


def people_only(twin: DigitalTwin, people: list, times: torch.Tensor) -> torch.Tensor:
    """The people's frames: ``twin``'s frames with them less those of the empty room.

    Args:
        twin: the twin.
        people: the people (anything with ``ellipsoids(t)``).
        times: frame start times ``(T,)``.

    Returns:
        Frames ``(T, RX, chirps, samples)``.
    """
    return twin.simulate(people, times) - twin.simulate([], times)


def traced(people: list, times: torch.Tensor, shadowing: bool) -> torch.Tensor:
    """The reference: one-chirp corridor frames, each traced at its own chirp's time, stacked.

    The same as :func:`radaraug.sim.figures.traced_at_every_chirp`, with the shadowing on or off.

    Args:
        people: the people.
        times: frame start times ``(T,)``.
        shadowing: whether the people shadow the room.

    Returns:
        Frames ``(T, RX, chirps, samples)``.
    """
    single = Scene.builtin("corridor")
    cfg = single.config
    single.config = cfg.replace(num_chirps_per_frame=1)
    m = cfg.num_chirps_per_frame
    tc = (times[:, None] + torch.arange(m, dtype=torch.float64) * cfg.chirp_repetition_time_s).reshape(-1)
    stacked = people_only(ideal_twin(single, intra_frame=0, shadowing=shadowing), people, tc)
    return stacked.reshape(len(times), m, *stacked.shape[1:]).squeeze(3).transpose(1, 2)


def twins(scene: Scene) -> dict[str, DigitalTwin]:
    """The twins of the table's columns: ``"0"``, ``"1"``, ``"2"``, ``"4"`` (shadow intervals) and ``"none"``.

    Args:
        scene: the room.

    Returns:
        The twins by column.
    """
    out = {str(k): ideal_twin(scene, shadow_intervals=k) for k in INTERVALS}
    out["none"] = ideal_twin(scene, shadowing=False)
    return out


def rod_row(scene: Scene) -> dict[str, float]:
    """The rod's Doppler-profile RMS error (dB) per column, bins within 30 dB of the reference's peak.

    Args:
        scene: the corridor.

    Returns:
        RMS error by column.
    """
    rod = TurningRod()
    times = rod_frame_times(ROD_FRAMES)
    refs = {True: doppler_profiles_db(traced([rod], times, True)),
            False: doppler_profiles_db(traced([rod], times, False))}
    out = {}
    for column, twin in twins(scene).items():
        ref = refs[column != "none"]
        sel = ref > ref.amax(dim=1, keepdim=True) - 30
        err = doppler_profiles_db(people_only(twin, [rod], times)) - ref
        out[column] = float(err[sel].square().mean().sqrt())
    return out


def walker_row(scene: Scene) -> dict[str, list[float]]:
    """The walker's largest difference off zero Doppler per frame, dB under the reference profile's peak.

    Args:
        scene: the corridor.

    Returns:
        Per-frame values by column.
    """
    walker = Walker(start=(2.0, 0.3), heading_rad=0.0)
    times = torch.arange(WALKER_FRAMES, dtype=torch.float64) * (1.1 / WALKER_FRAMES)
    refs = {True: traced([walker], times, True), False: traced([walker], times, False)}
    rd = RangeDoppler()

    def profile(x: torch.Tensor) -> torch.Tensor:
        return rd(x).abs().square().mean(dim=1).sum(dim=1)  # (T, chirps), zero Doppler centred

    out = {}
    for column, twin in twins(scene).items():
        ref = refs[column != "none"]
        diff = profile(people_only(twin, [walker], times) - ref)
        m = diff.shape[-1]
        off = torch.arange(m) != m // 2
        out[column] = (10 * torch.log10(diff[:, off].amax(dim=1) / profile(ref).amax(dim=1))).tolist()
    return out


def main() -> None:
    """Measure the table and write the record."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", type=Path, default=Path("benchmarks/shadowing_tables_cpu.json"),
                        help="the record to write (JSON)")
    args = parser.parse_args()
    start = time.perf_counter()
    scene = Scene.builtin("corridor")
    tables = {"in_frame_shadow": {
        "rod": {"frames": ROD_FRAMES, "doppler_profile_rms_error_db": rod_row(scene)},
        "walker": {"frames": WALKER_FRAMES, "largest_off_zero_doppler_difference_db_re_peak": walker_row(scene)},
    }}
    record = {"benchmark": "docs/shadowing.md in-frame shadow table: twin with shadow_intervals=K vs a trace at "
                           "every chirp (corridor, ideal receiver, no multipath, float64)",
              "command": COMMAND, "torch": torch.__version__, "device": "cpu",
              "elapsed_s": round(time.perf_counter() - start, 1), "tables": tables}
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(record, indent=2) + "\n")
    print(json.dumps(record, indent=2))


if __name__ == "__main__":
    main()
