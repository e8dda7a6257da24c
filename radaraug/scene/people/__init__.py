"""People for the digital twin: a procedural walker, BVH motion capture, animated mesh sequences.

Every person gives 16 moving ellipsoids (:meth:`Person.ellipsoids`, fast, for analytic
scattering) and a triangle mesh with per-vertex velocities (:meth:`Person.mesh`, for the ray
tracer). World frame: metres, ``z`` up, ground at ``z = 0``.
"""

from radaraug.scene.people.bvh import BVHSkeleton, read_bvh
from radaraug.scene.people.bvh_person import BVHPerson
from radaraug.scene.people.bvh_writer import write_bvh
from radaraug.scene.people.mesh_sequence import MeshSequencePerson
from radaraug.scene.people.person import Person, SkeletonPerson, person_from_dict
from radaraug.scene.people.simplify import simplify_mesh
from radaraug.scene.people.skeleton import JOINT_NAMES, SEGMENT_NAMES, Skeleton
from radaraug.scene.people.standing import StandingPerson
from radaraug.scene.people.walker import Walker

__all__ = [
    "BVHPerson", "BVHSkeleton", "JOINT_NAMES", "MeshSequencePerson", "Person", "SEGMENT_NAMES",
    "Skeleton", "SkeletonPerson", "StandingPerson", "Walker", "person_from_dict", "read_bvh", "simplify_mesh", "write_bvh",
]
