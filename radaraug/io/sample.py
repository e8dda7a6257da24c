"""The sample recording bundled with radaraug (MIT licensed, see its LICENSE and data card)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

SAMPLE_RECORDING = "zharfanw_breathing"


def sample_recording_path() -> Path:
    """Folder of the bundled BGT60TR13C recording: one person breathing about 0.3 m away.

    256 frames of 3 RX x 8 chirps x 64 samples (58-63.5 GHz, 12.9 frames/s, about 20 s),
    in Infineon's recording layout, so ``open_capture(sample_recording_path())`` reads it.
    For tests and demos, not for training.

    Raises:
        FileNotFoundError: the package was installed without its data files.
    """
    folder = resources.files("radaraug") / "data" / SAMPLE_RECORDING
    path = Path(str(folder))
    if not (path / "RadarIfxAvian_00" / "radar.npy").is_file():
        raise FileNotFoundError(f"radaraug's sample recording is missing from the installed package ({path})")
    return path
