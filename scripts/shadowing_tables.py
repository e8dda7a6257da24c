"""The tables of docs/shadowing.md, measured with the current code.

Inside a frame
--------------

A thin rod (0.6 m) turning at 6 rad/s 2.6 m out (:class:`radaraug.sim.figures.TurningRod`, 6 frames
0.14 s apart) and the limbs check's walker (``Walker(start=(2.0, 0.3), heading_rad=0.0)``, 4 frames
over 1.1 s) in the built-in corridor, ideal receiver, no multipath, float64: the twin with its shadow
held for the frame (``shadow_intervals=0``) or moved inside it (``K = 1, 2, 4``) against 64 one-chirp
frames each traced at its own chirp's time (:func:`radaraug.sim.figures.traced_at_every_chirp`). The
last column, "none", turns the shadowing off in both the twin and the reference.

- rod: RMS difference (dB) of the Doppler profiles over the bins within 30 dB of the reference's peak.
- walker: per frame, the largest power of the difference's Doppler profile off zero Doppler, dB under
  the reference profile's peak.

Walker between the radar and a metal wall
-----------------------------------------

:func:`radaraug.raytrace.figures.plot_walker_shadowing` (the page's figure, drawn into a temporary folder
and dropped): a metal wall at 8 m, radar at 1.25 m, a 1.8 m walker at 1.4 m/s crossing the line at 4 m
and walking along it (241 positions each); the model (all segments, two passes) against the torso's
knife edge and the physical-optics integral over the torso's ellipse.

A person in front of a room's end wall
--------------------------------------

The change (dB) of the end wall's zero-Doppler power (three range bins around its peak beyond 15 m, RX
mean, one frame) when a standing 1.8 m person (no breathing, no sway) stands 5.6 m down the corridor on
the line of sight, 0.25 m and 0.75 m off it; the whole twin (every path, shadowing, the person's own
scattering and multipath), ideal receiver, the slow test's setup (tests/sim/test_twin_shadowing.py).
In the built-in corridor (also with the people's multipath off); over 32 corridors (width and height
+-10 cm, radar height +-5 cm, drawn from ``torch.Generator().manual_seed(2026)``, the same draws as the
test): the change of the summed powers and each corridor's own change; the random-phase sum
``sum |T_i|^2 P_i / sum P_i`` over the static paths within 1.2 m of the bins (each path's own power
``P_i`` in the bins through the receiver, Hann window, RX 0) in the first of those corridors (the
test's reference) and in the built-in one, where also the coherent sum of those paths against the sum
of their powers and the largest ``|T_i|`` (person on the line) are recorded.

Cost
----

Wall times on this machine (one torch thread; the CPU and its core count are recorded): the shadow
test on a dense case (16 frames x 2 walkers x 5,000 static paths: 2,000 single-bounce and 3,000
double-bounce paths from a radar at (0.1, 3, 1.2) m to random points on the far and side walls of a
10 m x 6 m x 2.7 m room, drawn from ``torch.Generator().manual_seed(0)``, both walkers inside it),
float32 and float64; ``DigitalTwin.shadow_transmission`` of the two-walker corridor over a 16-frame
batch; ``DigitalTwin.static_basis`` of the corridor. Each time is the median (and mean) of repeated
calls after one warm-up call.

Deterministic except the times. Command::

    python scripts/shadowing_tables.py -o benchmarks/shadowing_tables_cpu.json
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import platform
import statistics
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import torch

from radaraug.config import RadarConfig
from radaraug.raytrace.figures import plot_walker_shadowing
from radaraug.raytrace.shadow import shadow_transmission
from radaraug.scene.geometry import Ellipsoids
from radaraug.scene.people import StandingPerson, Walker
from radaraug.scene.scene import Scene
from radaraug.scene.scene_file import builtin_scene, read_scene_data
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.figures import TurningRod, doppler_profiles_db, rod_frame_times
from radaraug.sim.twin import DigitalTwin
from radaraug.transforms import RangeDoppler

COMMAND = "python scripts/shadowing_tables.py -o benchmarks/shadowing_tables_cpu.json"
INTERVALS = (0, 1, 2, 4)
ROD_FRAMES = 6
WALKER_FRAMES = 4
END_WALL_OFFSETS_M = (0.0, 0.25, 0.75)
END_WALL_CORRIDORS = 32
COST_REPEATS = 15


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


def metal_wall_table() -> dict[str, Any]:
    """The metal-wall table: the summary of :func:`plot_walker_shadowing` (its figure is dropped).

    Returns:
        The drops (dB, two-way) by row and column.
    """
    with tempfile.TemporaryDirectory() as folder:
        r = plot_walker_shadowing(Path(folder) / "walker_shadowing.png")
    cols = {"model": "model", "knife_edge": "knife_edge", "physical_optics": "po"}
    return {
        "wall_m": 8.0, "radar_height_m": 1.25, "walker_speed_m_s": 1.4, "positions_per_walk": 241,
        "crossing_at_4_m_closest_pass_db": {k: r[f"cross_{v}_db_closest"] for k, v in cols.items()},
        "crossing_mean_while_torso_covers_db": {k: r[f"cross_{v}_db_mean_covered"] for k, v in cols.items()},
        "along_the_line_mean_2_to_6_m_db": {k: r[f"along_{v}_db_mean"] for k, v in cols.items()},
        "walker_over_1_m_off_the_line_largest_abs_model_db": r["cross_model_db_max_off_line"],
    }


def corridor(width: float, height: float, radar_z: float) -> Scene:
    """The built-in corridor with another width, height and radar height.

    Args:
        width: corridor width, metres.
        height: corridor height, metres.
        radar_z: radar height, metres.

    Returns:
        The scene.
    """
    data = read_scene_data(builtin_scene("corridor"))
    data["room"] = {**data["room"], "width": width, "height": height}
    data["radar"] = {**data["radar"], "position": [0.1, 0.0, radar_z], "look_at": [10.0, 0.0, radar_z]}
    return Scene.from_dict(data)


def end_wall_twin(scene: Scene, multipath: bool = True) -> DigitalTwin:
    """The whole twin of ``scene`` (float32, every path) with an ideal receiver, as the slow test builds it."""
    return DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=[]), tracer_options={"rays": 48},
                       multipath=multipath)


def zero_doppler_power(twin: DigitalTwin, people: list, times: torch.Tensor) -> torch.Tensor:
    """Zero-Doppler power per range bin of one simulated frame (RX mean), float64."""
    x = twin.simulate(people, times, generators=torch.Generator().manual_seed(0))
    return RangeDoppler()(x).abs().square().mean(dim=(0, 1))[:, twin.config.num_chirps_per_frame // 2].double()


def people_at_the_end_wall() -> dict[float, StandingPerson]:
    """The standing person 5.6 m down the corridor at each lateral offset."""
    return {lat: StandingPerson(height_m=1.8, position=(5.6, lat), facing_rad=3.14159, breathing_m=0.0, sway_rad=0.0)
            for lat in END_WALL_OFFSETS_M}


def wall_bin_changes(twin: DigitalTwin) -> tuple[slice, float, dict[float, float]]:
    """The end wall's three bins, their empty power and their power with the person at each offset.

    Args:
        twin: the twin of a corridor.

    Returns:
        The bins, the empty room's power in them and the power with the person by offset.
    """
    times = twin.frame_times([0])
    empty = zero_doppler_power(twin, [], times)
    start = int(15 / twin.config.range_resolution_m)
    k = start + int(empty[start:].argmax())
    bins = slice(k - 1, k + 2)
    with_person = {lat: float(zero_doppler_power(twin, [p], times)[bins].sum())
                   for lat, p in people_at_the_end_wall().items()}
    return bins, float(empty[bins].sum()), with_person


def db(ratio: float) -> float:
    """``10 log10(ratio)``."""
    return 10 * math.log10(ratio)


def random_phase_sum(twin: DigitalTwin, bins: slice) -> dict[str, Any]:
    """``10 log10(sum |T_i|^2 P_i / sum P_i)`` over the static paths within 1.2 m of the wall's bins.

    ``P_i``: path ``i``'s own power in the bins (RX 0, Hann window; the receiver is linear, one path at a
    time). Also the coherent sum of those paths in the bins against the sum of their powers, and the
    largest ``|T_i|`` of those paths with the person on the line.

    Args:
        twin: the twin of a corridor.
        bins: the wall's bins.

    Returns:
        ``{"by_offset_db": {offset: dB}, "paths": n, "coherent_vs_power_sum_db": dB, "largest_abs_t_on_the_line": x}``.
    """
    paths = twin.tracer.static_paths()
    n = twin.config.num_samples_per_chirp
    window = torch.hann_window(n, periodic=False, dtype=torch.float64)
    r = paths.delay_s[:, 0] * 299792458.0 / 2
    centre = (bins.start + 1) * twin.config.range_resolution_m
    near = ((r - centre).abs() < 1.2).nonzero().flatten()
    powers, coherent = [], torch.zeros(bins.stop - bins.start, dtype=torch.complex128)
    for i in near.tolist():
        keep = torch.zeros(paths.amplitude.shape[0], 1, dtype=paths.amplitude.dtype)
        keep[i] = 1
        one = twin.receiver.static_signal(dataclasses.replace(paths, amplitude=paths.amplitude * keep))[0, 0]
        spectrum = torch.fft.fft(one.double() * window)[bins]
        powers.append(float(spectrum.abs().square().sum()))
        coherent = coherent + spectrum
    pw = torch.tensor(powers, dtype=torch.float64)
    times = twin.frame_times([0])
    out: dict[str, float] = {}
    largest = 0.0
    for lat, person in people_at_the_end_wall().items():
        t = twin.shadow_transmission([person], times)
        assert t is not None
        tn = t[0][near].abs().double()
        out[str(lat)] = db(float((tn.square() * pw).sum() / pw.sum()))
        if lat == 0.0:
            largest = float(tn.max())
    return {"by_offset_db": out, "paths": int(near.numel()),
            "coherent_vs_power_sum_db": db(float(coherent.abs().square().sum() / pw.sum())),
            "largest_abs_t_on_the_line": largest}


def end_wall_table() -> dict[str, Any]:
    """The end-wall table: the built-in corridor, the mean over 32 corridors and the random-phase sums.

    Returns:
        The changes (dB) by row and offset (keys: the offset in metres as a string).
    """
    builtin = end_wall_twin(Scene.builtin("corridor"))
    bins, empty, person = wall_bin_changes(builtin)
    builtin_reference = random_phase_sum(builtin, bins)
    _, empty_off, person_off = wall_bin_changes(end_wall_twin(Scene.builtin("corridor"), multipath=False))
    g = torch.Generator().manual_seed(2026)
    sums = {"empty": 0.0, **{lat: 0.0 for lat in END_WALL_OFFSETS_M}}
    each: dict[str, list[float]] = {str(lat): [] for lat in END_WALL_OFFSETS_M}
    first: dict[str, Any] = {}
    for v in range(END_WALL_CORRIDORS):
        u = torch.rand(3, generator=g, dtype=torch.float64)
        twin = end_wall_twin(corridor(2.0 + 0.2 * float(u[0]) - 0.1, 2.7 + 0.2 * float(u[1]) - 0.1,
                                      1.2 + 0.1 * float(u[2]) - 0.05))
        bins_v, empty_v, person_v = wall_bin_changes(twin)
        sums["empty"] += empty_v
        for lat in END_WALL_OFFSETS_M:
            sums[lat] += person_v[lat]
            each[str(lat)].append(db(person_v[lat] / empty_v))
        if v == 0:
            first = random_phase_sum(twin, bins_v)
    return {
        "person": "StandingPerson(height_m=1.8, position=(5.6, offset), facing_rad=3.14159, breathing_m=0.0, "
                  "sway_rad=0.0)",
        "builtin_corridor_change_db": {str(lat): db(person[lat] / empty) for lat in END_WALL_OFFSETS_M},
        "builtin_corridor_no_people_multipath_change_db": {str(lat): db(person_off[lat] / empty_off)
                                                           for lat in END_WALL_OFFSETS_M},
        "corridors": END_WALL_CORRIDORS, "seed": 2026,
        "mean_over_corridors_change_db": {str(lat): db(sums[lat] / sums["empty"]) for lat in END_WALL_OFFSETS_M},
        "each_corridor_change_db": each,
        "random_phase_sum_first_corridor": first,
        "random_phase_sum_builtin_corridor": builtin_reference,
    }


def timed_ms(call: Callable[[], Any], repeats: int = COST_REPEATS) -> dict[str, float]:
    """Median and mean wall time (ms) of ``call`` over ``repeats`` calls after one warm-up call."""
    call()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(1e3 * (time.perf_counter() - start))
    return {"median_ms": statistics.median(times), "mean_ms": statistics.mean(times), "repeats": repeats}


def dense_case() -> tuple[torch.Tensor, Ellipsoids, float, int]:
    """The dense cost case: static-path vertices ``(5000, 4, 3)``, two walkers' segments over 16 frames.

    Returns:
        Vertices, segments (float64), wavelength and frame count.
    """
    g = torch.Generator().manual_seed(0)
    radar = torch.tensor([0.1, 3.0, 1.2], dtype=torch.float64)

    def wall_points(n: int) -> torch.Tensor:  # uniform on the far wall (x = 10 m) and the side walls (y = 0, 6 m)
        wall = torch.randint(0, 3, (n,), generator=g)
        s = torch.rand(n, generator=g, dtype=torch.float64)
        z = 2.7 * torch.rand(n, generator=g, dtype=torch.float64)
        x = torch.where(wall == 0, torch.full_like(s, 10.0), 10.0 * s)
        y = torch.where(wall == 0, 6.0 * s, torch.where(wall == 1, 0.0, 6.0))
        return torch.stack([x, y, z], -1)

    single, first, second = wall_points(2000), wall_points(3000), wall_points(3000)
    r1, r2 = radar.expand(2000, 3), radar.expand(3000, 3)
    vertices = torch.cat([torch.stack([r1, single, r1, r1], 1), torch.stack([r2, first, second, r2], 1)])
    cfg = RadarConfig.bgt60tr13c()
    frames = 16
    times = torch.arange(frames, dtype=torch.float64) * cfg.frame_repetition_time_s
    walkers = [Walker(start=(3.0, 2.0), heading_rad=0.4),
               Walker(start=(7.5, 4.2), heading_rad=math.pi + 0.3, speed_m_s=1.0)]
    return vertices, Ellipsoids.cat([w.ellipsoids(times) for w in walkers]), cfg.wavelength_m, frames


def cost_table() -> dict[str, Any]:
    """The cost figures: the dense case per frame (float32, float64), the corridor's batch and static basis.

    Returns:
        Times (ms) and counts.
    """
    vertices, ell, wavelength, frames = dense_case()
    dense: dict[str, Any] = {"frames": frames, "walkers": 2, "segments": int(ell.centers.shape[1]),
                             "static_paths": int(vertices.shape[0]), "single_bounce": 2000, "double_bounce": 3000}
    for name, dtype in (("float32", torch.float32), ("float64", torch.float64)):
        e = Ellipsoids(*(x.to(dtype) for x in (ell.centers, ell.semi_axes, ell.rotations, ell.velocities)))
        v = vertices.to(dtype)
        batch = timed_ms(lambda v=v, e=e: shadow_transmission(v, e, wavelength))
        dense[name] = {"per_frame_median_ms": batch["median_ms"] / frames, "per_frame_mean_ms": batch["mean_ms"] / frames,
                       "repeats": batch["repeats"]}
        if dtype == torch.float32:
            t = shadow_transmission(v, e, wavelength)
            dense["affected_paths_per_frame_mean"] = float(((t - 1).abs() > 1e-3).sum(dim=1).double().mean())
    scene = Scene.builtin("corridor_two_walkers")
    twin = DigitalTwin(scene)
    times = twin.frame_times(range(16))
    batch = timed_ms(lambda: twin.shadow_transmission(scene.people, times))
    basis = []
    for _ in range(3):  # a fresh twin each time: the basis is computed once per twin
        fresh = DigitalTwin(Scene.builtin("corridor"))
        fresh.tracer.static_paths()
        start = time.perf_counter()
        fresh.static_basis()
        basis.append(time.perf_counter() - start)
    return {"dense_case": dense,
            "two_walker_corridor_16_frames": {"static_paths": int(twin.tracer.static_paths().num_paths), **batch},
            "corridor_static_basis_s": {"median_s": statistics.median(basis), "runs": len(basis)}}


def cpu_name() -> str:
    """The CPU's model name where the system gives it, else the architecture."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def main() -> None:
    """Measure the tables and write the record."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", type=Path, default=Path("benchmarks/shadowing_tables_cpu.json"),
                        help="the record to write (JSON)")
    args = parser.parse_args()
    torch.set_num_threads(1)
    start = time.perf_counter()
    scene = Scene.builtin("corridor")
    tables = {"in_frame_shadow": {
        "rod": {"frames": ROD_FRAMES, "doppler_profile_rms_error_db": rod_row(scene)},
        "walker": {"frames": WALKER_FRAMES, "largest_off_zero_doppler_difference_db_re_peak": walker_row(scene)},
    }}
    tables["walker_metal_wall"] = metal_wall_table()
    tables["person_end_wall"] = end_wall_table()
    tables["cost"] = cost_table()
    record = {"benchmark": "docs/shadowing.md tables: the in-frame shadow (twin with shadow_intervals=K vs a trace at "
                           "every chirp; corridor, ideal receiver, no multipath, float64), a walker before a metal "
                           "wall, a person before a corridor's end wall (one corridor and 32), the shadow's cost",
              "command": COMMAND, "torch": torch.__version__, "device": "cpu", "cpu": cpu_name(),
              "cpu_count": os.cpu_count(), "torch_threads": torch.get_num_threads(),
              "elapsed_s": round(time.perf_counter() - start, 1), "tables": tables}
    args.output.parent.mkdir(parents=True, exist_ok=True)
    args.output.write_text(json.dumps(record, indent=2) + "\n")
    print(json.dumps(record, indent=2))


if __name__ == "__main__":
    main()
