"""The twin's fast shadowing (static basis) equals the explicit correction paths."""

from __future__ import annotations

import pytest
import torch

from radaraug.errors import ConfigError
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


def test_shadow_method_paths_in_simulate_and_t0():
    """``DigitalTwin(shadow_method="paths")`` gives :meth:`simulate` the same frames (to rounding);
    ``t0`` moves the receiver's clock only."""
    from radaraug.sensor.effects import SpurTone
    from radaraug.sim.randomization import ItemDraw

    scene = Scene.from_dict({"radar": {"position": [0.1, 0.0, 1.2], "look_at": [5.0, 0.0, 1.2]},
                             "room": {"type": "corridor", "length": 6.0, "width": 2.0, "height": 2.7}})
    chain = [SpurTone(freq_Hz=233e3, amplitude_counts=[0.4, 0.4, 0.4])]
    fast = DigitalTwin(scene, receiver=FMCWReceiver(scene.config, effects=chain), intra_frame=0)
    people = [Walker(start=(4.0, -0.6), heading_rad=1.2)]
    times = fast.frame_times(range(2)) * 4
    draw = ItemDraw(variant=0, system_gain_offset_dB=0.0, noise_figure_offset_dB=0.0, rcs_scale_dB=(1.0,))
    frames = {}
    for d in (None, draw):
        for method in ("signal", "paths"):
            fast.shadow_method = method  # the same twin: its room is traced once
            frames[method] = fast.simulate(people, times, draw=d)
        a, b = frames["signal"], frames["paths"]
        assert float((a - b).abs().max()) < 1e-4 * float(a.abs().max())
        base = a
    # The spur is time-locked: t0 = one spur period leaves the frames; half a period turns its sign.
    period = 1 / 233e3
    torch.testing.assert_close(fast.simulate(people, times, draw=draw, t0=1000 * period), base,
                               atol=1e-4 * float(base.abs().max()), rtol=0)
    assert not torch.allclose(fast.simulate(people, times, draw=draw, t0=period / 2), base)
    with pytest.raises(ConfigError):
        DigitalTwin(scene, shadow_method="basis")
