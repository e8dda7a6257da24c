"""Closing the loop with measured data: residual views, the effect catalog, the search, twin profiles.

``radaraug diagnose`` (or :func:`diagnose` + :func:`write_report`) compares a capture with the twin,
adds the sensor effects that explain the residual and writes a report and a fitted
:class:`TwinProfile`. What one empty-room capture calibrates is one :class:`CalibrationRecord`
(:func:`radaraug.diagnosis.record.fit_record`, :func:`load_record`). See ``docs/diagnosis.md``.
"""

from radaraug.diagnosis.catalog import CATALOG_NAMES, Candidate, ParamSpec, catalog
from radaraug.diagnosis.diagnose import Diagnosis, diagnose, locate_unexplained, write_report
from radaraug.diagnosis.search import Search, SearchResult, SearchSettings
from radaraug.diagnosis.twin_source import TwinSource
from radaraug.diagnosis.views import VIEW_NAMES, Views, compute_views, overall_error, view_errors
from radaraug.sensor.profile import TwinProfile
from radaraug.transforms.record_file import CalibrationRecord, load_record

__all__ = [
    "CATALOG_NAMES",
    "Candidate",
    "ParamSpec",
    "catalog",
    "CalibrationRecord",
    "load_record",
    "Diagnosis",
    "diagnose",
    "locate_unexplained",
    "write_report",
    "Search",
    "SearchResult",
    "SearchSettings",
    "TwinSource",
    "VIEW_NAMES",
    "Views",
    "compute_views",
    "overall_error",
    "view_errors",
    "TwinProfile",
]
