"""Room parameters the calibration loop fits: properties of the traced room, not receiver effects.

In scene mode the loop can also fit how strongly the room scatters diffusely
(:mod:`radaraug.raytrace.diffuse`): one power gain ``diffuse_gain_dB`` on every diffuse path,
the :class:`~radaraug.raytrace.RayTracer` option of the same name. It is not a stage of the
receiver, so it does not go into the effect chain: the search carries a separate ``room`` dict
next to the chain, and its parameter lists name it with the pseudo-stage :data:`ROOM_STAGE`.
:class:`~radaraug.calibration.twin_source.TwinSource` applies a candidate value without tracing
again (the diffuse and specular paths are synthesized apart, the diffuse signal scaled by
``10**(g/20)``). The fitted values land in the twin profile's ``room`` section
(:class:`~radaraug.sensor.profile.TwinProfile`).

Why only a gain and not the scattering coefficient ``S`` itself: a diffuse path's field is
proportional to ``S`` (``sigma0`` goes as ``S^2`` for both patterns), but the specular part keeps
``sqrt(1 - S^2)`` of the field *per bounce* and per material (a three-bounce path carries three
factors, glass and metal have their own ``S``), and the merge of the image method's paths mixes
them: no single factor on the traced specular paths is exact for a change of ``S``. A pure gain
on the diffuse power is exact (it is what the tracer's ``diffuse_gain_dB`` does: the specular
part is left as traced), so that is what is fitted.
"""

from __future__ import annotations

from radaraug.sensor.effects.base import Prior

ROOM_STAGE = "room"
"""Pseudo-stage name of the room parameters in the search's ``(stage, ParamSpec)`` lists."""

Room = dict[str, float]
"""Room parameter values by name (e.g. ``{"diffuse_gain_dB": 4.2}``)."""

ROOM_PRIORS: dict[str, Prior] = {
    # The default S = 0.7 was fitted to two real rooms within ~5 dB; +-20 dB covers a bare
    # concrete box (S ~ 0.1, -17 dB) up to a cluttered room, linear in dB like every gain.
    "diffuse_gain_dB": Prior(-20.0, 20.0, "lin"),
}
"""Search range of each room parameter."""

__all__ = ["ROOM_PRIORS", "ROOM_STAGE", "Room"]
