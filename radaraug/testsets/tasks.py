"""The tasks and their classes: what a capture's people count means for each task."""

from __future__ import annotations

from typing import Any

import torch

from radaraug.errors import ConfigError

#: Class names per task; the label of a simulated item or a capture's frame is its people count.
TASKS: dict[str, tuple[str, ...]] = {"occupancy": ("empty", "occupied"), "counting": ("0", "1", "2")}
#: The people counts each task accepts: counting's classes, or any count >= 0 for occupancy.
COUNTING_COUNTS = (0, 1, 2)


def check_task(task: str) -> tuple[str, ...]:
    """The class names of ``task`` (ConfigError for an unknown task)."""
    if task not in TASKS:
        raise ConfigError(f"task must be one of {sorted(TASKS)}, got {task!r}")
    return TASKS[task]


def label_of(count: int | torch.Tensor, task: str) -> Any:
    """The class label of a people count for ``task`` (occupancy: count > 0)."""
    if task == "occupancy":
        return (count > 0).long() if isinstance(count, torch.Tensor) else int(count > 0)
    return count
