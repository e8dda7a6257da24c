"""Base classes of radaraug transforms: torchvision-v2 / kornia style ``nn.Module``s (docs/transforms.md)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import torch
from torch import nn
from torch.utils import _pytree as pytree

from radaraug.errors import InputTensorError, RadarAugError
from radaraug.transforms import _sample
from radaraug.transforms._checks import check_tensor
from radaraug.transforms._rng import GeneratorSource, draw

Params = dict[str, torch.Tensor]


class RadarTransform(nn.Module):
    """A deterministic radar transform; inputs are never modified in place.

    Subclasses set :attr:`kernel` and :attr:`spec_fields` (the kernel's keyword arguments), or override
    :meth:`transform` (and :meth:`extra_spec` when they have parameters).
    """

    #: trailing dims that make one sample (the event); leading dims are batch dims.
    event_ndim: int = 3
    #: human description of the expected input, used in error messages.
    input_layout: str = "(..., rx, range, doppler)"
    #: accept complex input.
    accepts_complex: bool = False
    #: Takes whole samples (tuples, dicts) itself (read by ``_sample.is_sample_aware``).
    takes_samples: bool = True
    #: The attributes :meth:`extra_spec` reports: the step's parameters, named as its kernel's arguments.
    spec_fields: tuple[str, ...] = ()
    #: The functional kernel (a ``staticmethod``) the default :meth:`transform` calls.
    kernel: Callable[..., torch.Tensor] | None = None

    def check_input(self, x: Any) -> torch.Tensor:
        """Validate the input (rank, dtype, NaN/Inf) and return it."""
        return check_tensor(
            x,
            f"{type(self).__name__} expects {self.input_layout}",
            min_ndim=self.event_ndim,
            allow_complex=self.accepts_complex,
        )

    def transform(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        """Compute the output for a validated input: ``kernel(x, **extra_spec())`` unless overridden."""
        if self.kernel is None:  # pragma: no cover - abstract
            raise NotImplementedError
        return self.kernel(x, **self.extra_spec())

    def is_radar_tensor(self, leaf: Any) -> bool:
        """Whether a leaf of a sample is one this transform works on (see :mod:`._sample`)."""
        return _sample.eligible(leaf, self.event_ndim, self.accepts_complex)

    def select(self, sample: Any) -> tuple[list[Any], Any, list[int]]:
        """Flatten ``sample`` and validate its radar leaves.

        Returns:
            ``(leaves, spec, chosen)``: the flat leaves, the tree spec (None for a plain tensor) and the
            indices of the radar leaves, each checked with :meth:`check_input`.

        Raises:
            InputTensorError: no leaf is a radar tensor, or one fails :meth:`check_input`.
        """
        if isinstance(sample, torch.Tensor):
            return [self.check_input(sample)], None, [0]
        flat, spec = pytree.tree_flatten(sample)
        chosen = _sample.radar_leaves(flat, self.is_radar_tensor)
        if not chosen:
            likely = _sample.most_likely_radar_leaf(flat, self.event_ndim)
            if likely is not None:
                self.check_input(likely)  # raises the precise problem (dtype, rank, ...)
            raise InputTensorError(
                f"{type(self).__name__} expects {self.input_layout}: expected a torch.Tensor, or a "
                f"tuple/list/dict holding one; got a {type(sample).__name__} with no tensor in it"
            )
        for i in chosen:
            flat[i] = self.check_input(flat[i])
        return flat, spec, chosen

    def forward(self, *inputs: Any) -> Any:
        """Transform a tensor, or the radar leaves of a sample."""
        flat, spec, chosen = self.select(_sample.as_sample(inputs))
        for i in chosen:
            flat[i] = self.transform(flat[i], {})
        return flat[0] if spec is None else pytree.tree_unflatten(flat, spec)

    def extra_spec(self) -> dict[str, Any]:
        """The transform's parameters (its :attr:`spec_fields`) as JSON types."""
        return {k: getattr(self, k) for k in self.spec_fields}

    def chain_spec(self) -> dict[str, Any]:
        """``{"name": class name, **parameters}``: this step of a DSP chain, JSON-able."""
        return {"name": type(self).__name__, **self.extra_spec()}

    def extra_repr(self) -> str:
        """The parameters of :meth:`extra_spec` for ``repr``."""
        return ", ".join(f"{k}={v!r}" for k, v in self.extra_spec().items())


class RandomRadarTransform(RadarTransform):
    """A random radar transform with per-sample parameters (a sample: one item of the batch dims).

    Subclasses implement :meth:`sample_params` and :meth:`transform` and extend :attr:`spec_fields`.

    Args:
        p: probability of applying the transform, drawn per sample.
        same_on_batch: draw one set of parameters for the whole batch.
        generator: a ``torch.Generator`` to draw from (else ``seed``, else the global RNG).
        seed: seed of a generator the transform owns (one per device; pickles).
        reseed_in_workers: re-seed ``generator``/``seed`` per DataLoader worker so workers differ;
            ``False`` makes every worker replay the same stream.
    """

    spec_fields: tuple[str, ...] = ("p", "same_on_batch")

    def __init__(
        self,
        p: float = 1.0,
        same_on_batch: bool = False,
        generator: torch.Generator | None = None,
        *,
        seed: int | None = None,
        reseed_in_workers: bool = True,
    ) -> None:
        super().__init__()
        p = float(p)
        if not 0.0 <= p <= 1.0:
            raise RadarAugError(f"{type(self).__name__}: p must be in [0, 1], got {p}")
        if generator is not None and seed is not None:
            raise RadarAugError(f"{type(self).__name__}: give either generator or seed, not both")
        self.p = p
        self.same_on_batch = bool(same_on_batch)
        self.rng = GeneratorSource(generator, seed, reseed_in_workers)
        self.last_params: Params | None = None

    # ------------------------------------------------------------------ random draws
    def param_shape(self, x: torch.Tensor) -> tuple[int, ...]:
        """Shape of per-sample parameters: the batch dims, or all ones with ``same_on_batch``."""
        batch = tuple(x.shape[: x.ndim - self.event_ndim])
        return tuple(1 for _ in batch) if self.same_on_batch else batch

    #: Uniform [0, 1) or normal draws with ``like``'s dtype and device (:func:`._rng.draw`).
    draw = staticmethod(draw)

    def make_params(self, x: torch.Tensor, generator: torch.Generator | None = None) -> Params:
        """Draw the parameters for ``x``: ``apply`` (bool, per sample) and the subclass's own."""
        shape = self.param_shape(x)
        if 0.0 < self.p < 1.0:
            apply = self.draw("rand", shape, x, generator) < self.p
        else:  # p = 0 or 1: nothing to draw
            apply = torch.full(shape, self.p >= 1.0, dtype=torch.bool, device=x.device)
        return {"apply": apply, **self.sample_params(x, shape, generator)}

    def sample_params(
        self, x: torch.Tensor, shape: tuple[int, ...], generator: torch.Generator | None
    ) -> Params:  # pragma: no cover - abstract
        """The subclass's parameters, with leading dims ``shape`` (broadcastable to the batch)."""
        raise NotImplementedError

    # ------------------------------------------------------------------ application
    def forward(self, *inputs: Any, params: Mapping[str, torch.Tensor] | None = None) -> Any:
        """Transform a tensor (or a sample's radar leaves) with fresh parameters, or replay ``params``.

        ``params`` (a mapping with an ``"apply"`` key, e.g. ``t.last_params``) may also be the second positional
        argument. The parameters (drawn from the first radar leaf) are applied to every radar leaf and kept
        in ``last_params``.
        """
        if params is None and len(inputs) > 1 and isinstance(inputs[1], Mapping) and "apply" in inputs[1]:
            params, inputs = inputs[1], (inputs[0], *inputs[2:])
        sample = _sample.as_sample(inputs)
        flat, spec, chosen = self.select(sample)
        if params is None and not self.training:
            self.last_params = None
            return sample
        x = flat[chosen[0]]
        # Fresh draws with p = 1 (the default) apply to every sample: skip _apply_where's two host syncs.
        every = params is None and self.p >= 1.0
        if params is None:
            params = self.make_params(x, self.rng.get(x.device))
        else:
            params = {k: torch.as_tensor(v, device=x.device) for k, v in params.items()}
        self.last_params = dict(params)
        for i in chosen:
            flat[i] = self.transform(flat[i], params) if every else self._apply_where(flat[i], params)
        return flat[0] if spec is None else pytree.tree_unflatten(flat, spec)

    def _apply_where(self, x: torch.Tensor, params: Params) -> torch.Tensor:
        apply = params["apply"]
        if not bool(apply.any()):
            return x
        y = self.transform(x, params)
        if bool(apply.all()):
            return y
        mask = apply.reshape(apply.shape + (1,) * self.event_ndim)
        return torch.where(mask, y, x)

    def chain_spec(self) -> dict[str, Any]:
        """As :meth:`RadarTransform.chain_spec`, marked ``"random": True``."""
        return {**super().chain_spec(), "random": True}
