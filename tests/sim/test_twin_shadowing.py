"""The twin's fast shadowing (static basis) equals the explicit correction paths."""

from __future__ import annotations

import torch

from radaraug.scene.people import Walker
from radaraug.scene.scene import Scene
from radaraug.sensor.receiver import FMCWReceiver
from radaraug.sim.twin import DigitalTwin


def test_static_basis_route_equals_correction_paths():
    scene = Scene.builtin("corridor")
    twin = DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=[]), dtype=torch.float64,
                       intra_frame=0)
    walker = Walker(start=(4.0, -0.6), heading_rad=1.2)  # crosses the boresight line at ~5 m
    times = twin.frame_times(range(4)) * 4
    people = [walker]
    static = twin.static_signal()
    shadow = twin.shadow_signal(people, times)
    assert shadow is not None and shadow.shape == (4, scene.config.num_rx, 1, scene.config.num_samples_per_chirp)
    fast = twin.receiver(twin.paths(people, times), static_signal=static + shadow, frame_start_s=times)
    explicit = twin.receiver(twin.frame_paths(people, times), static_signal=static, frame_start_s=times)
    err = (fast - explicit).norm() / (explicit - twin.receiver(twin.paths(people, times), static_signal=static,
                                                                 frame_start_s=times)).norm()
    assert float(err) < 1e-4  # relative to the shadow's own effect (fast synthesis: ~1e-6)
    # A static path's signal is the same on every chirp (what the basis relies on).
    one = twin.tracer.static_paths().map(lambda x: x[:3, None])
    sig = twin.receiver.static_signal(one)
    torch.testing.assert_close(sig, sig[:, :, :1].expand_as(sig))
