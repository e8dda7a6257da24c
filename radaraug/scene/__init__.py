"""Scenes: rooms as triangle meshes with materials, people, and the radar's pose."""

from radaraug.scene.geometry import Ellipsoids, RadarPose, SceneGeometry
from radaraug.scene.materials import (
    MATERIALS,
    Material,
    fresnel_coefficients,
    get_material,
    material_table,
    reflection_coefficients,
    register_material,
    slab_reflection,
    slab_transmission,
)
from radaraug.scene.room import CORRIDOR_SURFACES, PAPER_CORRIDOR_MATERIALS, corridor, load_mesh, merge
from radaraug.scene.scene import Scene, builtin_scene

__all__ = [
    "CORRIDOR_SURFACES",
    "MATERIALS",
    "PAPER_CORRIDOR_MATERIALS",
    "Scene",
    "builtin_scene",
    "corridor",
    "load_mesh",
    "merge",
    "Ellipsoids",
    "Material",
    "RadarPose",
    "SceneGeometry",
    "fresnel_coefficients",
    "get_material",
    "material_table",
    "reflection_coefficients",
    "register_material",
    "slab_reflection",
    "slab_transmission",
]
