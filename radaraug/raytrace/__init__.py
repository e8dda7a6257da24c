"""Vectorized torch ray tracer: shooting-and-bouncing rays + physical optics -> `Paths`.

Entry point: :class:`RayTracer` (static room paths traced once and cached, moving targets per
snapshot) and :func:`paths_to_json`. Building blocks: :func:`intersect` / :func:`any_hit`
(batched Möller–Trumbore style tests), :class:`TriangleBVH`, the PO integrals in
:mod:`radaraug.raytrace.po` and antenna patterns (the kernel's benchmark is
:func:`radaraug.bench.intersection.benchmark_intersection`).
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
