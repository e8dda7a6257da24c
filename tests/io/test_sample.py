"""The bundled sample recording: shipped, readable, and what its data card says it is."""

from __future__ import annotations

import numpy as np
import torch

from radaraug.io import InfineonRecording, open_capture, sample_recording_path


def test_sample_recording_is_bundled_with_its_licence():
    path = sample_recording_path()
    assert (path / "LICENSE").read_text().count("M Zharfan Wiranata") == 1
    assert (path / "meta.json").is_file()
    with open_capture(path) as cap:
        assert isinstance(cap, InfineonRecording)
        assert cap.shape == (256, 3, 8, 64)
        assert cap.config.num_samples_per_chirp == 64 and cap.config.if_gain_dB == 23
        counts = cap.read(as_float=False)
    # Figures from the recording's description: min 1070, max 2450, mean 1870.7 counts.
    assert counts.min() == 1070 and counts.max() == 2450
    assert abs(counts.double().mean().item() - 1870.7) < 0.05


def test_sample_recording_shows_breathing_near_0_3_m():
    """Slow-time phase of the 0.30-0.36 m range bins oscillates at about 0.25 Hz (15 breaths/min)."""
    with open_capture(sample_recording_path()) as cap:
        x = cap.read().double()
        config = cap.config
    x = x - x.mean(dim=-1, keepdim=True)
    window = torch.hann_window(config.num_samples_per_chirp, periodic=False, dtype=torch.float64)
    profile = torch.fft.rfft(x * window, dim=-1).mean(dim=2)  # (frame, rx, range)
    ranges = np.asarray(config.range_axis_m())
    bins = np.flatnonzero((ranges > 0.29) & (ranges < 0.37))
    freqs = np.fft.rfftfreq(cap.num_frames, 1 / config.frame_rate_Hz)
    for b in bins:
        phase = np.unwrap(np.angle(profile[:, 0, b].numpy()))
        phase -= phase.mean()
        spectrum = np.abs(np.fft.rfft(phase * np.hanning(len(phase))))
        assert abs(freqs[1:][np.argmax(spectrum[1:])] - 0.25) < 0.05
        assert np.ptp(phase) > 10  # radians: chest motion of a few mm at 5 mm wavelength
