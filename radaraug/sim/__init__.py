"""On-the-fly simulation: the digital twin, its Dataset, offline generation (docs/simulation.md).

* :class:`DigitalTwin`: a scene's people at frame times -> raw ADC frames;
* :class:`SimulatedRadarDataset`: a torch Dataset whose item ``i`` is a pure function of (seed, i);
* :class:`ScenarioSampler` / :class:`Scenario`: who walks where; :class:`TwinRandomization`: per-item draws;
* :func:`simulate_capture`: a scene simulated into a radaraug HDF5 capture (sharded, resumable);
* :func:`item_generator` / :func:`item_seed`: the per-item seeding; :class:`Stream`: its named streams.
"""

from radaraug.sim.dataset import SimulatedRadarDataset
from radaraug.sim.offline import simulate_capture
from radaraug.sim.randomization import TwinRandomization
from radaraug.sim.scenarios import Scenario, ScenarioSampler
from radaraug.sim.seeding import Stream, item_generator, item_seed
from radaraug.sim.twin import DigitalTwin

__all__ = [
    "DigitalTwin",
    "Scenario",
    "ScenarioSampler",
    "SimulatedRadarDataset",
    "Stream",
    "TwinRandomization",
    "item_generator",
    "item_seed",
    "simulate_capture",
]
