"""VirtualSensor: a pure function of (seed, frame index), paced like a sensor or as fast as possible."""

from __future__ import annotations

import time

import numpy as np
import pytest
import torch

from radaraug.capture import Frame, VirtualSensor
from radaraug.errors import DeviceError
from radaraug.io import open_capture
from radaraug.sim.offline import simulate_capture
from radaraug.units import float_to_counts


def test_same_seed_same_frames_other_seed_other_frames(cfg) -> None:
    a = VirtualSensor("corridor", config=cfg, seed=3, realtime=False)
    with a:
        streamed = torch.stack([a.next_frame().data for _ in range(20)])
    b = VirtualSensor("corridor", config=cfg, seed=3, realtime=False)
    assert torch.equal(streamed, b.frames(0, 20))
    # Any frame alone (another block boundary, out of order) is the same.
    assert torch.equal(b.frames(17, 18)[0], streamed[17])
    other = VirtualSensor("corridor", config=cfg, seed=4, realtime=False).frames(0, 20)
    assert not torch.equal(streamed, other)
    assert streamed.shape == (20, cfg.num_rx, cfg.num_chirps_per_frame, cfg.num_samples_per_chirp)
    assert streamed.dtype == torch.float32 and streamed.abs().max() <= 1.0


def test_frames_equal_what_radaraug_simulate_writes(tmp_path, cfg) -> None:
    # The offline simulator is another code path over the same (seed, block) noise streams.
    out = simulate_capture("corridor", tmp_path / "sim.h5", frames=20, seed=5, progress=False,
                           twin_options={"config": cfg})
    with open_capture(out["path"]) as cap:
        want = cap.read(as_float=False).numpy()
    got = float_to_counts(VirtualSensor("corridor", config=cfg, seed=5).frames(0, 20)).numpy()
    assert np.array_equal(got, want)


def test_frame_timestamps_and_indices(cfg) -> None:
    with VirtualSensor("corridor", config=cfg, realtime=False) as s:
        frames = [s.next_frame() for _ in range(3)]
    assert all(isinstance(f, Frame) for f in frames)
    assert [f.index for f in frames] == [0, 1, 2]
    assert [f.timestamp for f in frames] == pytest.approx([0.0, cfg.frame_repetition_time_s, 2 * cfg.frame_repetition_time_s])
    assert not s.running
    with pytest.raises(DeviceError, match="not started"):
        s.next_frame()


def test_realtime_is_paced_at_the_frame_rate_and_fast_mode_is_not(cfg) -> None:
    n = 12
    sensor = VirtualSensor("corridor", config=cfg, realtime=True)
    sensor.start()
    t0 = time.monotonic()
    for _ in range(n):
        sensor.next_frame()
    elapsed = time.monotonic() - t0
    sensor.stop()
    nominal = (n - 1) * cfg.frame_repetition_time_s + cfg.num_chirps_per_frame * cfg.chirp_repetition_time_s
    assert 0.8 * nominal <= elapsed <= nominal + 1.0
    slow = cfg.replace(frame_repetition_time_s=0.5)  # 32 frames = 16 s of real time
    fast = VirtualSensor("corridor", config=slow, realtime=False)
    fast.start()
    t0 = time.monotonic()
    for _ in range(32):
        fast.next_frame()
    assert time.monotonic() - t0 < 5.0
    fast.stop()
