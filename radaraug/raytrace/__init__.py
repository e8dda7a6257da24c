"""Vectorized torch ray tracer: scene + radar -> propagation `Paths` for the FMCW receiver.

Entry point: :class:`RayTracer` and :func:`paths_to_json`; building blocks :func:`intersect` /
:func:`any_hit`, :class:`TriangleBVH` and the PO integrals of :mod:`radaraug.raytrace.po`. See
``docs/raytracer.md``.
"""

from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import IsotropicAntenna, PatchAntenna
from radaraug.raytrace.intersect import Hit, any_hit, compile_enabled, intersect
from radaraug.raytrace.merge import merge_paths
from radaraug.raytrace.po import facet_root_rcs, plane_wave_rcs
from radaraug.raytrace.targets import ellipsoid_rcs
from radaraug.raytrace.tracer import RayTracer, paths_to_json

__all__ = [
    "Hit",
    "IsotropicAntenna",
    "PatchAntenna",
    "RayTracer",
    "TriangleBVH",
    "any_hit",
    "compile_enabled",
    "ellipsoid_rcs",
    "facet_root_rcs",
    "intersect",
    "merge_paths",
    "paths_to_json",
    "plane_wave_rcs",
]
