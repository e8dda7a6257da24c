"""The training methods as objects: a recipe's ``data.method``, a ``class_path`` entry.

A method is the noise-floor randomization (DR) a run trains with and the twin that goes with it:
:class:`RT` (none), :class:`RandomDR` (drawn from fixed ranges), :class:`CDR` (fitted on the empty-room
capture, on a quiet twin), :class:`CDRProfile` (CDR's DR on a twin whose receiver is fitted on that
capture) and :class:`OwnDR` (a DR module of yours). docs/training.md, "Methods".
"""

from __future__ import annotations

import importlib
import inspect
import os
from typing import Any, ClassVar, Literal

from torch import nn

from radaraug.errors import ConfigError

#: CalibratedDR floors a CDR run can ask for: CalibratedDR's own (``normal``: the paper's, ``empirical``:
#: the capture's measured distribution) and ``matched`` (the clamp's quantiles matched to the twin's own
#: empty-room floor so that ``max(S, N)`` has the capture's law: :mod:`radaraug.transforms.floor_fit`).
CDR_FLOORS = ("normal", "empirical", "matched")


class Method:
    """What every method has: its DR, and what it asks of the calibration capture and the twin.

    Each constructor argument is kept as the attribute of the same name (:meth:`init_args` reads them).

    Args:
        test_dr: pass the test captures through the DR too (not the paper's protocol).
    """

    #: the method's name in reports and recipe files (``method/NAME.yaml``)
    name: ClassVar[str] = ""
    #: its DR is fitted on the empty-room capture (or read from a calibration record)
    needs_calibration: ClassVar[bool] = False
    #: its twin's receiver is the twin profile fitted on the empty-room capture
    fits_profile: ClassVar[bool] = False
    #: the CalibratedDR floor asked for (None: not a CDR method, or the calibration's own)
    floor: str | None = None
    #: dB by which the twin's noise is lowered so that the DR supplies the floor (None: not lowered)
    twin_noise_offset_db: float | None = None

    def __init__(self, test_dr: bool = False) -> None:
        self.test_dr = bool(test_dr)

    def dr(self, calibration: str | os.PathLike | None, seed: int) -> nn.Module | None:
        """The run's DR on per-RX dB maps ``(B, rx, range, doppler)`` (None: no randomization)."""
        return None

    def init_args(self) -> dict[str, Any]:
        """The constructor's arguments as plain values (a recipe's ``init_args``; an object as its repr)."""
        args = {k: getattr(self, k) for k in inspect.signature(type(self)).parameters}
        return {k: v if v is None or isinstance(v, (bool, int, float, str, list)) else repr(v) for k, v in args.items()}

    def to_dict(self) -> dict[str, Any]:
        """The recipe entry: ``{"class_path": ..., "init_args": ...}``."""
        cls = type(self)
        return {"class_path": f"{cls.__module__}.{cls.__qualname__}", "init_args": self.init_args()}

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Method) and self.to_dict() == other.to_dict()

    def __hash__(self) -> int:
        return hash(repr(self))

    def __repr__(self) -> str:
        return f"{type(self).__name__}({', '.join(f'{k}={v!r}' for k, v in self.init_args().items())})"


class RT(Method):
    """Trained on the twin with no noise-floor randomization (the paper's RT)."""

    name = "rt"


class RandomDR(Method):
    """The noise floor drawn per sample from fixed ranges (:class:`radaraug.transforms.RandomDR`).

    Args:
        mean_db: range of the floor's mean in dB (None: the transform's default).
        std_db: range of the floor's standard deviation in dB (None: the default).
        test_dr: as :class:`Method`.
    """

    name = "randomdr"

    def __init__(self, mean_db: list[float] | None = None, std_db: list[float] | None = None,
                 test_dr: bool = False) -> None:
        super().__init__(test_dr)
        self.mean_db = None if mean_db is None else [float(v) for v in mean_db]
        self.std_db = None if std_db is None else [float(v) for v in std_db]

    def dr(self, calibration: str | os.PathLike | None, seed: int) -> nn.Module:
        """A :class:`radaraug.transforms.RandomDR` seeded with ``seed``."""
        from radaraug.transforms import RandomDR as RandomDRTransform

        ranges: dict[str, Any] = {k: tuple(v) for k, v in (("mean_db", self.mean_db), ("std_db", self.std_db))
                                  if v is not None}
        return RandomDRTransform(seed=seed, **ranges)


class CDR(Method):
    """The paper's CalibratedDR: the floor's statistics fitted on the empty-room capture.

    Args:
        floor: ``normal`` (the paper's), ``empirical``, ``matched`` (default: the measured chain), or None
            (the calibration's own).
        twin_noise_offset_db: lower the twin's noise by this many dB so that the clamp supplies the floor,
            as in the paper (None: the other methods' twin).
        test_dr: as :class:`Method`.

    Raises:
        ConfigError: an unknown floor.
    """

    name = "cdr"
    needs_calibration = True

    def __init__(self, floor: Literal["normal", "empirical", "matched"] | None = "matched",
                 twin_noise_offset_db: float | None = -15.0, test_dr: bool = False) -> None:
        super().__init__(test_dr)
        if floor is not None and floor not in CDR_FLOORS:
            raise ConfigError(f"CDR floor must be one of {CDR_FLOORS} or null, got {floor!r}")
        self.floor = floor
        self.twin_noise_offset_db = None if twin_noise_offset_db is None else float(twin_noise_offset_db)

    def dr(self, calibration: Any, seed: int) -> nn.Module:
        """The CalibratedDR of ``calibration`` (a capture is fitted, a JSON loaded, a fitted one copied) with this floor.

        ``matched`` gives the empirical floor here; the data module then matches its quantiles to the
        twin's empty-room floor.

        Raises:
            ConfigError: no calibration.
        """
        from radaraug.training.pipeline import is_calibration_json
        from radaraug.transforms import CalibratedDR

        if calibration is None:
            raise ConfigError(f"method {self.name!r} needs a calibration: an empty-room capture or a calibration record")
        fitted: CalibratedDR
        if isinstance(calibration, CalibratedDR):
            fitted = calibration
        else:
            fitted = (CalibratedDR.load(calibration) if is_calibration_json(calibration)
                      else CalibratedDR.fit(calibration, progress=False))
        floor = "empirical" if self.floor == "matched" else self.floor
        return fitted.replace(floor=floor or fitted.floor, seed=seed)


class CDRProfile(CDR):
    """CDR's DR on a twin whose receiver is the twin profile ``radaraug diagnose`` fits on the capture.

    A profile given as ``data.twin.profile`` is used instead of fitting one.

    Args:
        floor: as :class:`CDR`.
        max_frames: calibration frames the fit reads.
        test_dr: as :class:`Method`.
    """

    name = "cdr_profile"
    fits_profile = True

    def __init__(self, floor: Literal["normal", "empirical", "matched"] | None = "matched", max_frames: int = 100,
                 test_dr: bool = False) -> None:
        super().__init__(floor, None, test_dr)
        self.max_frames = int(max_frames)


class OwnDR(Method):
    """A DR module of yours on the plain twin (``RT``'s and ``RandomDR``'s).

    Args:
        module: the DR on per-RX dB maps ``(B, rx, range, doppler)``, used as given on every rank.
        test_dr: as :class:`Method`.
    """

    name = "own_dr"

    def __init__(self, module: nn.Module, test_dr: bool = False) -> None:
        super().__init__(test_dr)
        self.module = module

    def dr(self, calibration: str | os.PathLike | None, seed: int) -> nn.Module:
        """``module``."""
        return self.module


#: The methods ``radaraug reproduce`` runs, by name.
METHODS: dict[str, type[Method]] = {m.name: m for m in (RT, RandomDR, CDR, CDRProfile)}


def method_from(spec: Method | str | dict[str, Any]) -> Method:
    """A method from itself, its name (``"cdr"``: its defaults) or a recipe entry (``class_path``, ``init_args``).

    Raises:
        ConfigError: an unknown name or class, or arguments it does not take.
    """
    if isinstance(spec, Method):
        return spec
    if isinstance(spec, str):
        if spec not in METHODS:
            raise ConfigError(f"method must be one of {sorted(METHODS)} or a class_path entry, got {spec!r}")
        return METHODS[spec]()
    if not isinstance(spec, dict) or "class_path" not in spec:
        raise ConfigError(f"method must be a name or a mapping with class_path (and init_args), got {spec!r}")
    path = str(spec["class_path"])
    module, _, attr = path.rpartition(".")
    try:
        cls = getattr(importlib.import_module(module), attr) if module else globals().get(attr)
    except (ImportError, AttributeError):
        cls = None
    if not (isinstance(cls, type) and issubclass(cls, Method)):
        raise ConfigError(f"method class_path {path!r} is not a radaraug.training.methods.Method: one of "
                          f"{sorted(m.__qualname__ for m in (*METHODS.values(), OwnDR))} or a subclass")
    args = dict(spec.get("init_args") or {})
    unknown = set(args) - set(inspect.signature(cls).parameters)
    if unknown:
        raise ConfigError(f"method {cls.__qualname__} takes no {sorted(unknown)}")
    return cls(**args)
