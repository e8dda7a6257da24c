"""Radar captures: radaraug's HDF5 format, Infineon recordings, and a torch Dataset over them.

:func:`open_capture` reads either kind; :class:`CaptureWriter` records HDF5 captures crash-safely;
:class:`RadarCaptureDataset` serves them to a DataLoader. Format: ``docs/captures.md``. This package
knows nothing of transforms.
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
