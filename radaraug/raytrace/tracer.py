"""`RayTracer`: scene + radar -> :class:`~radaraug.sensor.paths.Paths` (static room + moving targets).

The room does not move, so its SBR paths are traced once (:meth:`RayTracer.static_paths`,
cached) and merged coherently into few paths. Targets are traced per snapshot by
:meth:`RayTracer.target_paths`: the ellipsoid model is pure tensor work over any leading
(time) dims, so a batch of frames costs a handful of tensor ops.
"""

from __future__ import annotations

import math
from typing import Any

import torch

from radaraug.config import SPEED_OF_LIGHT, RadarConfig
from radaraug.errors import SceneError
from radaraug.raytrace.accel import TriangleBVH
from radaraug.raytrace.antenna import PatchAntenna
from radaraug.raytrace.merge import merge_paths
from radaraug.raytrace.radar import RadarGeometry
from radaraug.raytrace.rays import ray_grid
from radaraug.raytrace.reflect import FaceReflectivity
from radaraug.raytrace.sbr import shoot_and_bounce
from radaraug.raytrace.targets import MirrorPlanes, ellipsoid_paths, mesh_po_paths
from radaraug.scene.geometry import Ellipsoids, RadarPose, SceneGeometry
from radaraug.sensor.paths import Paths


class RayTracer:
    """Vectorized SBR + PO ray tracer of one radar in one static room.

    Args:
        room: static scene (walls, floor, ceiling, furniture); its ``vertex_velocity`` is ignored.
        radar: pose of the radar's antenna frame.
        config: radar configuration (carrier, TX/RX positions).
        max_bounces: most surface interactions per SBR ray (1 = single scattering).
        rays: SBR rays per axis of the gnomonic grid, ``n`` or ``(nu, nv)``.
        fov_deg: half field of view of the SBR grid per axis, degrees.
        antenna: TX/RX pattern with ``gain(dirs)`` (default :class:`PatchAntenna`, 6 dBi assumed).
        polarization: radar E-field direction in the radar frame (default ``y``, an assumption).
        merge_bin_m: path-length bin of the coherent merge of the static SBR paths (None: no merge).
        floor_dB: merged static paths weaker than this relative to the strongest are dropped.
        mirror_min_area_m2: planar face groups at least this large act as multipath mirrors.
        device: torch device (default: the room's).
        dtype: real dtype of the computation and of the returned paths.
    """

    def __init__(
        self,
        room: SceneGeometry,
        radar: RadarPose,
        config: RadarConfig,
        *,
        max_bounces: int = 2,
        rays: int | tuple[int, int] = 512,
        fov_deg: float | tuple[float, float] = 70.0,
        antenna: Any = None,
        polarization: tuple[float, float, float] = (0.0, 1.0, 0.0),
        merge_bin_m: float | None = 0.01,
        floor_dB: float = -100.0,
        mirror_min_area_m2: float = 1.0,
        device: torch.device | str | None = None,
        dtype: torch.dtype = torch.float32,
    ) -> None:
        if not isinstance(max_bounces, int) or max_bounces < 1:
            raise SceneError(f"max_bounces must be a positive integer, got {max_bounces!r}")
        _check_scene(room, "room")
        self.device = torch.device(device) if device is not None else room.vertices.device
        self.dtype = dtype
        self.config = config
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
        self._static: Paths | None = None

    def static_paths(self) -> Paths:
        """The room's SBR paths ``(P, RX)`` (traced on the first call, then cached)."""
        if self._static is None:
            if self.bvh is None:
                z = torch.zeros(0, self.radar.rx.shape[0], dtype=self.dtype, device=self.device)
                self._static = Paths(z, z.clone(), z.to(_complex(self.dtype)),
                                     torch.zeros(0, dtype=torch.int8, device=self.device))
            else:
                tubes = ray_grid(self.rays, self.fov_deg, self.radar.tx, self.radar.rotation)
                paths = shoot_and_bounce(self.bvh, self.face_material, self.reflectivity, self.radar, tubes,
                                         self.antenna, max_bounces=self.max_bounces)
                if self.merge_bin_m:
                    paths = merge_paths(paths, self.frequency_Hz, bin_m=self.merge_bin_m, floor_dB=self.floor_dB)
                self._static = paths
        return self._static

    def target_paths(
        self,
        ellipsoids: Ellipsoids | None = None,
        meshes: list[SceneGeometry] | None = None,
        multipath: bool = True,
    ) -> Paths:
        """Paths of moving targets.

        Args:
            ellipsoids: body segments ``(..., S)``; leading dims (e.g. ``T`` frames) carry
                through to the result ``(..., P, RX)``.
            meshes: meshes at one instant (PO on every facet); only without leading dims on
                ``ellipsoids``.
            multipath: add first-order multipath of the ellipsoids via the room's mirror planes.

        Returns:
            :class:`Paths` with ``kind`` and ``mask`` (masked slots are occluded segments or
            multipath that does not exist for that snapshot).
        """
        parts: list[Paths] = []
        lead: tuple[int, ...] = ()
        if ellipsoids is not None:
            lead = tuple(ellipsoids.centers.shape[:-2])
            parts.append(ellipsoid_paths(
                ellipsoids, self.radar, self.antenna, room_bvh=self.bvh, room_face_material=self.face_material,
                room_reflectivity=self.reflectivity, mirrors=self.mirrors if multipath else None,
                frequency_Hz=self.frequency_Hz, convex_room=self.convex_room,
            ))
        for i, mesh in enumerate(meshes or []):
            _check_scene(mesh, f"meshes[{i}]")
            if lead:
                raise SceneError("meshes are single snapshots: they cannot be combined with ellipsoids that "
                                 f"have leading dims {lead}; trace them per frame")
            refl = FaceReflectivity(mesh.materials, self.frequency_Hz, self.device, self.dtype)
            parts.append(mesh_po_paths(mesh, self.radar, self.antenna, refl, room_bvh=self.bvh))
        if not parts:
            z = torch.zeros(*lead, 0, self.radar.rx.shape[0], dtype=self.dtype, device=self.device)
            return Paths(z, z.clone(), z.to(_complex(self.dtype)),
                         torch.zeros(*lead, 0, dtype=torch.int8, device=self.device),
                         torch.zeros(*lead, 0, dtype=torch.bool, device=self.device))
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


def _complex(dtype: torch.dtype) -> torch.dtype:
    return torch.complex128 if dtype == torch.float64 else torch.complex64


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
    """A JSON-ready summary of paths (for ``radaraug trace SCENE --json``).

    Per path: ``delay_ns`` (per RX), ``range_m`` (``c * mean delay / 2``),
    ``radial_velocity_m_s`` (``c * mean delay_rate / 2``, positive = receding), ``power_dB``
    (``10 log10`` of the mean over RX of ``|a|^2``: RX-port power relative to the TX power),
    ``rx_phase_deg`` (carrier phase of each RX, ``angle(a exp(-j 2 pi f_c tau))``) and ``kind``
    (``"los"`` single scattering, ``"multipath"``). Masked slots are left out; paths are sorted by
    range. Leading batch dims give ``{"snapshots": [...]}``.
    """
    if paths.delay_s.ndim > 2:
        flat = paths.delay_s.shape[:-2]
        n = math.prod(flat)

        flat_paths = paths.map(lambda x: x.reshape(n, *x.shape[len(flat):]))
        return {"batch_shape": list(flat), "snapshots": [
            paths_to_json(flat_paths.map(lambda x, i=i: x[i]), config)["paths"] for i in range(n)
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
