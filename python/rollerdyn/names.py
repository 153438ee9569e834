"""Names shared by the Rust core and the Python front: the roller end / flange pairings,
the four flange contacts of a roller and the contact detectors.

The values come from the core (``_core.PAIRINGS``, ``_core.FLANGES``,
``_core.DETECTORS``, built from its own tables and tested there); this module is their
one Python home: the configuration's ``solver.detector``, the
result file's ``pairing`` and ``flange`` coordinates, the ``--detector`` options and their
messages, the figures and the report all take them from here. Their order is the core's
(``flange_pairing`` holds an index into :data:`PAIRINGS`, the ``flange`` axis of a result
follows :data:`FLANGES`).
"""

from __future__ import annotations

from . import _core

__all__ = [
    "DETECTORS",
    "FLANGES",
    "GRADIENT",
    "MESH",
    "PAIRINGS",
    "RACES",
    "SEMI_ANALYTICAL",
    "flange_indices",
    "one_of",
]

PAIRINGS: tuple[str, ...] = tuple(_core.PAIRINGS)
"""Roller end / flange pairings, in the order of ``flange_pairing`` (paper fig. 1)."""

FLANGES: tuple[str, ...] = tuple(_core.FLANGES)
"""The four roller end / flange contacts of a roller: ring and side of the flange."""

RACES: tuple[str, ...] = ("inner", "outer")
"""The two races, as the names of the variables of their contacts begin."""


def flange_indices(ring: str) -> list[int]:
    """Indices into :data:`FLANGES` (the ``flange`` axis of a result) of the two flanges of
    ``ring``, ``"inner"`` or ``"outer"``."""
    return [k for k, f in enumerate(FLANGES) if f.startswith(ring)]


SEMI_ANALYTICAL, GRADIENT, MESH = _core.DETECTORS
"""The paper's semi-analytical detector (sect. 2.1, the default), Koch's gradient method
(sect. 2.2, for comparison) and triangle meshes (parry3d, a baseline)."""

DETECTORS: tuple[str, ...] = (SEMI_ANALYTICAL, GRADIENT, MESH)
"""The roller end / flange contact detectors (``solver.detector``, ``--detector``)."""


def one_of(names: tuple[str, ...]) -> str:
    """``("a", "b", "c")`` -> ``"a, b or c"``: the choices as a message lists them."""
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} or {names[-1]}"
