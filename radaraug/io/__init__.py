"""Radar captures: radaraug's HDF5 format, Infineon recordings, and a torch Dataset over them.

* :func:`open_capture` reads either kind and returns a :class:`CaptureReader`;
* :class:`CaptureWriter` / :func:`write_capture` record radaraug HDF5 captures (crash-safe);
* :func:`write_infineon_recording` writes Infineon's recording layout;
* :mod:`radaraug.io.blocks`: the block size and the one block writer of simulated captures;
* :class:`RadarCaptureDataset` serves frames or frame windows of many captures to a DataLoader;
* :func:`sample_recording_path` points at the small real recording shipped with radaraug.

The format is specified in ``docs/captures.md``. This package knows nothing of transforms.
"""

from radaraug.io.base import CaptureReader, CaptureWarning
from radaraug.io.dataset import RadarCaptureDataset
from radaraug.io.dispatch import open_capture
from radaraug.io.hdf5_format import FORMAT_NAME, FORMAT_VERSION
from radaraug.io.hdf5_reader import HDF5Capture
from radaraug.io.hdf5_writer import CaptureWriter, write_capture
from radaraug.io.infineon import InfineonRecording, write_infineon_recording
from radaraug.io.sample import sample_recording_path

__all__ = [
    "open_capture",
    "CaptureReader",
    "CaptureWarning",
    "CaptureWriter",
    "write_capture",
    "HDF5Capture",
    "InfineonRecording",
    "write_infineon_recording",
    "RadarCaptureDataset",
    "sample_recording_path",
    "FORMAT_NAME",
    "FORMAT_VERSION",
]
