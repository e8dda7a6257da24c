"""`RayTracer`: scene + radar -> :class:`~radaraug.sensor.paths.Paths` (static room + moving targets).

The static room is traced once and cached (:mod:`radaraug.raytrace.cache`): by default with the image
method, Fresnel-split facet PO and diffuse scattering, with no ray density to tune (``method="sbr"``: shooting
and bouncing rays). Targets are traced per snapshot, batched over any leading (time) dims. See
``docs/raytracer.md``.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.errors import SceneError
from radaraug.raytrace import cache as static_cache
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import Antenna, PatchAntenna
from radaraug.raytrace.diffuse import diffuse_paths
from radaraug.raytrace.facets import facet_paths
from radaraug.raytrace.images import image_paths
from radaraug.raytrace.merge import merge_paths, merge_paths_with_vertices
from radaraug.raytrace.radar import RadarGeometry
from radaraug.raytrace.rays import ray_grid
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.raytrace.sbr import shoot_and_bounce
from radaraug.raytrace.targets import MirrorPlanes, ellipsoid_paths, mesh_po_paths
from radaraug.scene.geometry import Ellipsoids, RadarPose, SceneGeometry
from radaraug.scene.materials import get_material
from radaraug.scene.scattering import ScatteringOverrides, get_scattering, specular_reduction
from radaraug.sensor.paths import Paths

STATIC_METHODS = ("image", "sbr")
STATIC_PARTS = ("all", "specular", "diffuse")
"""What :meth:`RayTracer.static_paths` can return."""
FACET_MERGE_BIN_M = 0.002
"""Path-length bin of the coherent merge of small-face PO paths (see the tracer's comment)."""
FACET_MERGE_VOXEL_M = 0.2
"""Voxel of that merge: a merged path's vertex stays within it (shadowing acts on the right place)."""
_CACHED_PATH_FIELDS = ("delay_s", "delay_rate", "amplitude", "kind")
"""The :class:`Paths` fields of a static cache entry, in the constructor's order."""


class RayTracer:
    """Vectorized ray tracer of one radar in one static room (image method + PO + diffuse, or SBR).

    Args:
        room: static scene (walls, floor, ceiling, furniture); its ``vertex_velocity`` is ignored.
        radar: pose of the radar's antenna frame.
        config: radar configuration (carrier, TX/RX positions).
        method: how the static room is traced: ``"image"`` (default) or ``"sbr"``.
        max_bounces: most specular reflections per static path (image method, default 3: trihedral corners)
            or surface interactions per SBR ray (default 2).
        rays: SBR rays per axis of the gnomonic grid, ``n`` or ``(nu, nv)`` (``method="sbr"``).
        fov_deg: half field of view of the SBR grid per axis, degrees (``method="sbr"``).
        antenna: TX/RX pattern with ``gain(dirs)`` (default :class:`PatchAntenna`, 6 dBi assumed).
        polarization: radar E-field direction in the radar frame (default ``y``, an assumption).
        merge_bin_m: path-length bin of the coherent merge of the static SBR paths (None: no merge; SBR only).
        floor_dB: merged static paths weaker than this relative to the strongest are dropped.
        mirror_min_area_m2: planar face groups at least this large act as mirrors (image method and
            people's multipath); smaller faces are scattered by facet PO.
        density: tightening of every sampled part of the image method (1 = the documented bound), for
            convergence checks.
        cache: keep the traced static room on disk (True: :func:`~radaraug.raytrace.cache.default_cache_dir`,
            a folder, or False).
        diffuse: add the diffuse scattering of rough surfaces (image method only); the specular reflections
            are then reduced by ``sqrt(1 - S^2)`` per material.
        scattering: per-material diffuse-scattering overrides (``Scene.scattering``).
        diffuse_gain_dB: one power gain on every diffuse path (what the calibration fits).
        diffuse_seed: seed of the diffuse scatterers (default: derived from the room's content).
        device: torch device (default: the room's).
        dtype: real dtype of the computation and of the returned paths.
    """

    def __init__(
        self,
        room: SceneGeometry,
        radar: RadarPose,
        config: RadarConfig,
        *,
        method: str = "image",
        max_bounces: int | None = None,
        rays: int | tuple[int, int] = 512,
        fov_deg: float | tuple[float, float] = 70.0,
        antenna: Antenna | None = None,
        polarization: tuple[float, float, float] = (0.0, 1.0, 0.0),
        merge_bin_m: float | None = 0.01,
        floor_dB: float = -100.0,
        mirror_min_area_m2: float = 1.0,
        density: float = 1.0,
        cache: bool | str | os.PathLike = True,
        diffuse: bool = True,
        scattering: ScatteringOverrides | None = None,
        diffuse_gain_dB: float = 0.0,
        diffuse_seed: int | None = None,
        device: torch.device | str | None = None,
        dtype: torch.dtype = torch.float32,
    ) -> None:
        if method not in STATIC_METHODS:
            raise SceneError(f"method must be one of {STATIC_METHODS}, got {method!r}")
        if max_bounces is None:
            max_bounces = 3 if method == "image" else 2
        if not isinstance(max_bounces, int) or isinstance(max_bounces, bool) or max_bounces < 1:
            raise SceneError(f"max_bounces must be a positive integer, got {max_bounces!r}")
        ray_counts = (rays, rays) if isinstance(rays, int) else tuple(rays)
        if len(ray_counts) != 2 or not all(isinstance(n, int) and not isinstance(n, bool) and n >= 1
                                           for n in ray_counts):
            raise SceneError(f"rays must be a positive ray count per axis or a pair of them, got {rays!r}")
        if not (isinstance(density, (int, float)) and math.isfinite(density) and density >= 1):
            raise SceneError(f"density must be a number >= 1, got {density!r}")
        _check_scene(room, "room")
        self.device = torch.device(device) if device is not None else room.vertices.device
        self.dtype = dtype
        self.config = config
        self.method = method
        self.density = float(density)
        self.mirror_min_area_m2 = mirror_min_area_m2
        self.polarization = tuple(polarization)
        self.diffuse = bool(diffuse) and method == "image"
        self.scattering = dict(scattering or {})
        if not math.isfinite(float(diffuse_gain_dB)):
            raise SceneError(f"diffuse_gain_dB must be finite, got {diffuse_gain_dB!r}")
        self.diffuse_gain_dB = float(diffuse_gain_dB)
        self.diffuse_seed = diffuse_seed
        self.max_bounces = max_bounces
        self.rays = rays
        self.fov_deg = fov_deg
        self.antenna = antenna if antenna is not None else PatchAntenna()
        self.merge_bin_m = merge_bin_m
        self.floor_dB = floor_dB
        self.frequency_Hz = config.center_frequency_Hz
        self.room = room
        self.radar = RadarGeometry.build(radar, config, polarization, self.device, dtype)
        self.bvh = TriangleBVH(room.triangles.to(device=self.device, dtype=dtype)) if room.num_faces else None
        self.face_material = room.face_material.to(self.device)
        self.reflectivity = FaceReflectivity(room.materials, self.frequency_Hz, self.device, dtype)
        self.mirrors = MirrorPlanes(room, mirror_min_area_m2, self.device, dtype) if room.num_faces else None
        # A convex room (a box corridor) blocks no leg between points inside it: skip ray casts.
        self.convex_room = self.mirrors is not None and self.mirrors.convex_enclosure(self.radar.centre)
        if cache is True:
            self.cache_dir: Path | None = static_cache.default_cache_dir()
        elif cache is False or cache is None:
            self.cache_dir = None
        else:
            self.cache_dir = Path(cache)
        self._static: tuple[Paths, torch.Tensor | None, torch.Tensor] | None = None

    def static_paths(self, part: str = "all") -> Paths:
        """The room's paths ``(P, RX)`` (traced on the first call, then kept in memory and on disk).

        Args:
            part: ``"all"`` (default), ``"specular"`` (everything but the diffuse scattering) or ``"diffuse"``
                (already scaled by ``diffuse_gain_dB``). The two parts partition ``"all"``, so a calibration can
                scale the diffuse one without tracing again.
        """
        if part not in STATIC_PARTS:
            raise SceneError(f"static_paths: part must be one of {STATIC_PARTS}, got {part!r}")
        paths, _, mask = self._traced_static()
        if part == "all":
            return paths
        keep = mask if part == "diffuse" else ~mask
        return paths.map(lambda x: x[keep])

    def static_diffuse_mask(self) -> torch.Tensor:
        """``(P,)`` bool over :meth:`static_paths`: True for the diffuse scattering paths."""
        return self._traced_static()[2]

    def static_vertices(self) -> torch.Tensor | None:
        """``(P, V, 3)`` vertices of :meth:`static_paths`, or None for ``method="sbr"`` (merged tubes).

        ``[radar centre, interaction points..., radar centre]``, padded by repeating the radar centre.
        """
        return self._traced_static()[1]

    def cache_key(self) -> str:
        """SHA-256 key of the static room (see :mod:`radaraug.raytrace.cache`)."""
        room = self.room
        parts: list[Any] = [
            "static-room", static_cache.TRACER_VERSION, self.method, self.max_bounces, self.density,
            self.mirror_min_area_m2, repr(self.antenna), self.polarization, self.merge_bin_m, self.floor_dB,
            str(self.dtype), *self._room_parts(),
            [repr(get_material(m)) for m in room.materials], self.radar.tx.double(), self.radar.rx.double(),
            self.radar.rotation.double(), float(self.config.center_frequency_Hz),
        ]
        if self.method == "sbr":
            parts += [self.rays, self.fov_deg]
        if self.diffuse:
            parts += ["diffuse", self.diffuse_gain_dB, self.diffuse_seed,
                      [repr(get_scattering(m, self.scattering)) for m in room.materials]]
        return static_cache.digest(parts)

    def _room_seed(self) -> int:
        """Seed of the diffuse scatterers: given, or from the room's geometry and materials."""
        if self.diffuse_seed is not None:
            return int(self.diffuse_seed)
        return int(static_cache.digest([*self._room_parts(), list(self.room.materials)])[:15], 16)

    def _room_parts(self) -> list[torch.Tensor]:
        """The room's geometry as digest parts (of the cache key and the diffuse seed)."""
        room = self.room
        return [room.vertices.to(torch.float64), room.faces.long(), room.face_material.long()]

    def _traced_static(self) -> tuple[Paths, torch.Tensor | None, torch.Tensor]:
        """``(paths, vertices, diffuse mask)`` of the static room: traced or loaded on the first call."""
        if self._static is None:
            self._static = self._load_or_trace_static()
        return self._static

    def _load_or_trace_static(self) -> tuple[Paths, torch.Tensor | None, torch.Tensor]:
        key = self.cache_key() if self.cache_dir is not None else ""
        if self.cache_dir is not None:
            hit = static_cache.load(self.cache_dir, key)
            # An entry written before the diffuse mask was stored cannot say which paths are
            # diffuse: traced again (and replaced) when the room has any.
            if hit is not None and ("diffuse" in hit or not self.diffuse):
                dev = self.device
                paths = Paths(*(hit[name].to(dev) for name in _CACHED_PATH_FIELDS))
                v = hit.get("vertices")
                d = hit.get("diffuse")
                diffuse = (d.to(device=dev, dtype=torch.bool) if d is not None else
                           torch.zeros(paths.num_paths, dtype=torch.bool, device=dev))
                return paths, None if v is None else v.to(dev), diffuse
        paths, vertices, diffuse = self._trace_static_uncached()
        if self.cache_dir is not None:
            assert paths.kind is not None  # every static tracer (images, facets, diffuse, SBR) sets it
            data = {name: getattr(paths, name).cpu() for name in _CACHED_PATH_FIELDS}
            data["diffuse"] = diffuse.cpu()
            if vertices is not None:
                data["vertices"] = vertices.cpu()
            static_cache.store(self.cache_dir, key, data)
        return paths, vertices, diffuse

    def _trace_static_uncached(self) -> tuple[Paths, torch.Tensor | None, torch.Tensor]:
        """``(paths, vertices, diffuse mask)`` of the static room."""
        if self.bvh is None:
            empty = Paths.empty(self.radar.rx.shape[0], dtype=self.dtype, device=self.device)
            return (empty, torch.zeros(0, self.max_bounces + 2, 3, dtype=self.dtype, device=self.device),
                    torch.zeros(0, dtype=torch.bool, device=self.device))
        if self.method == "sbr":
            tubes = ray_grid(self.rays, self.fov_deg, self.radar.tx, self.radar.rotation)
            paths = shoot_and_bounce(self.bvh, self.face_material, self.reflectivity, self.radar, tubes,
                                     self.antenna, max_bounces=self.max_bounces)
            if self.merge_bin_m:
                paths = merge_paths(paths, self.frequency_Hz, bin_m=self.merge_bin_m, floor_dB=self.floor_dB)
            return paths, None, torch.zeros(paths.num_paths, dtype=torch.bool, device=self.device)
        v_count = self.max_bounces + 2
        assert self.mirrors is not None
        room = self.room.to(self.device)
        # Rough surfaces send S^2 of the reflected power into the diffuse field: the coherent
        # (specular and facet-PO) reflection keeps sqrt(1 - S^2) of the field.
        spec = (specular_reduction(room.materials, self.scattering, device=self.device, dtype=self.dtype)
                if self.diffuse else None)
        parts = [image_paths(room, self.mirrors, self.radar, self.antenna, self.reflectivity,
                             max_order=self.max_bounces, specular_factor=spec)]
        small = (self.mirrors.face_plane.to(self.device) < 0).nonzero()[:, 0]
        if small.numel():
            fp, fv = facet_paths(self.bvh.triangles, small, self.face_material, self.radar, self.antenna,
                                 self.reflectivity, self.bvh, density=self.density, specular_factor=spec)
            # Merged finely: the non-specular PO of small faces is a sum of terms that nearly
            # cancel, so a 1 cm merge's phase error across the sweep (0.1 rad) was larger than
            # what is left (13 dB RMS off); 2 mm bins in 0.2 m voxels measured 0.09 dB RMS on the
            # furnished corridor (65k -> 8.6k paths).
            fp, fv = merge_paths_with_vertices(fp, fv, self.frequency_Hz, bin_m=FACET_MERGE_BIN_M,
                                               voxel_m=FACET_MERGE_VOXEL_M)
            parts.append((fp, _pad_vertices(fv, v_count)))
        if self.diffuse:
            dp, dv = diffuse_paths(room, self.radar, self.antenna, self.bvh, frequency_Hz=self.frequency_Hz,
                                   seed=self._room_seed(), scattering=self.scattering, gain_dB=self.diffuse_gain_dB)
            parts.append((dp, _pad_vertices(dv, v_count)))
        paths = Paths.cat([p for p, _ in parts])
        vertices = torch.cat([v for _, v in parts])
        diffuse = torch.zeros(paths.num_paths, dtype=torch.bool, device=self.device)
        if self.diffuse:
            diffuse[paths.num_paths - parts[-1][0].num_paths:] = True  # the diffuse part comes last
        return paths, vertices, diffuse

    def target_paths(
        self,
        ellipsoids: Ellipsoids | None = None,
        meshes: list[SceneGeometry] | None = None,
        multipath: bool = True,
        targets: torch.Tensor | None = None,
    ) -> Paths:
        """Paths of moving targets.

        Args:
            ellipsoids: body segments ``(..., S)``; leading dims (e.g. ``T`` frames) carry through to ``(..., P, RX)``.
            meshes: meshes at one instant (PO on every facet); only without leading dims on ``ellipsoids``.
            multipath: add the ellipsoids' multipath via the room's mirror planes.
            targets: only these segments' paths (indices, ascending; all segments still occlude), see
                :func:`~radaraug.raytrace.targets.ellipsoid_paths`.

        Returns:
            :class:`Paths` with ``kind`` and ``mask`` (masked: occluded segments, absent multipath).
        """
        parts: list[Paths] = []
        lead: tuple[int, ...] = ()
        if ellipsoids is not None:
            lead = tuple(ellipsoids.centers.shape[:-2])
            parts.append(ellipsoid_paths(
                ellipsoids, self.radar, self.antenna, room_bvh=self.bvh, room_face_material=self.face_material,
                room_reflectivity=self.reflectivity, mirrors=self.mirrors if multipath else None,
                frequency_Hz=self.frequency_Hz, convex_room=self.convex_room, targets=targets,
            ))
        for i, mesh in enumerate(meshes or []):
            _check_scene(mesh, f"meshes[{i}]")
            if lead:
                raise SceneError("meshes are single snapshots: they cannot be combined with ellipsoids that "
                                 f"have leading dims {lead}; trace them per frame")
            refl = FaceReflectivity(mesh.materials, self.frequency_Hz, self.device, self.dtype)
            parts.append(mesh_po_paths(mesh, self.radar, self.antenna, refl, room_bvh=self.bvh))
        if not parts:
            return Paths.empty(self.radar.rx.shape[0], dtype=self.dtype, device=self.device, lead=lead, mask=True)
        return Paths.cat(parts) if len(parts) > 1 else parts[0]

    def trace(
        self, ellipsoids: Ellipsoids | None = None, meshes: list[SceneGeometry] | None = None,
        multipath: bool = True,
    ) -> Paths:
        """Static room paths + target paths (static ones repeated over the targets' leading dims)."""
        targets = self.target_paths(ellipsoids, meshes, multipath)
        static = self.static_paths()
        lead = targets.delay_s.shape[:-2]
        if lead:
            static = static.map(lambda x: x.expand(*lead, *x.shape))
        return Paths.cat([static, targets])


def _pad_vertices(v: torch.Tensor, count: int) -> torch.Tensor:
    """Pad ``(P, V, 3)`` vertices to ``count`` by repeating the last one (the radar centre)."""
    if v.shape[1] >= count:
        return v
    return torch.cat([v, v[:, -1:].expand(-1, count - v.shape[1], -1)], dim=1)


def _check_scene(scene: SceneGeometry, name: str) -> None:
    v, f = scene.vertices, scene.faces
    if v.ndim != 2 or v.shape[-1] != 3:
        raise SceneError(f"{name}: vertices must be (V, 3), got {tuple(v.shape)}")
    if f.ndim != 2 or f.shape[-1] != 3:
        raise SceneError(f"{name}: faces must be (F, 3), got {tuple(f.shape)}")
    if f.numel() and (int(f.min()) < 0 or int(f.max()) >= v.shape[0]):
        raise SceneError(f"{name}: face indices must lie in [0, {v.shape[0]})")
    if scene.face_material.shape != f.shape[:1]:
        raise SceneError(f"{name}: face_material must be ({f.shape[0]},), got {tuple(scene.face_material.shape)}")
    if f.numel() and (int(scene.face_material.min()) < 0 or int(scene.face_material.max()) >= len(scene.materials)):
        raise SceneError(f"{name}: face_material indexes {len(scene.materials)} materials out of range")
    if not torch.isfinite(v).all():
        raise SceneError(f"{name}: vertices contain NaN or inf")


def paths_to_json(paths: Paths, config: RadarConfig) -> dict[str, Any]:
    """A JSON-ready summary of paths (for ``radaraug trace SCENE --json``; fields in ``docs/raytracer.md``).

    Masked slots are left out and paths sorted by range; leading batch dims give ``{"snapshots": [...]}``.
    """
    if paths.delay_s.ndim > 2:
        flat = paths.delay_s.shape[:-2]
        n = math.prod(flat)

        flat_paths = paths.map(lambda x: x.reshape(n, *x.shape[len(flat):]))
        return {"batch_shape": list(flat), "snapshots": [
            paths_to_json(flat_paths.select(i), config)["paths"] for i in range(n)
        ]}
    d = paths.delay_s.detach().double().cpu()
    rate = paths.delay_rate.detach().double().cpu()
    a = paths.amplitude.detach().to(torch.complex128).cpu()
    keep = torch.ones(d.shape[0], dtype=torch.bool) if paths.mask is None else paths.mask.cpu()
    kind = torch.zeros(d.shape[0], dtype=torch.int8) if paths.kind is None else paths.kind.cpu()
    carrier = a * torch.exp(-2j * math.pi * config.center_frequency_Hz * d)
    power = (a.abs() ** 2).mean(-1)
    order = torch.argsort(d.mean(-1))
    out = []
    for i in order.tolist():
        if not bool(keep[i]) or float(power[i]) <= 0:
            continue
        out.append({
            "delay_ns": [round(x * 1e9, 6) for x in d[i].tolist()],
            "range_m": round(float(d[i].mean()) * SPEED_OF_LIGHT / 2, 6),
            "radial_velocity_m_s": round(float(rate[i].mean()) * SPEED_OF_LIGHT / 2, 6),
            "power_dB": round(10 * math.log10(float(power[i])), 3),
            "rx_phase_deg": [round(math.degrees(x), 3) for x in torch.angle(carrier[i]).tolist()],
            "kind": "multipath" if int(kind[i]) else "los",
        })
    return {"convention": "power_dB = 10*log10(P_rx / P_tx) per path, mean over RX; phases at the carrier",
            "num_paths": len(out), "paths": out}
