"""Scene delegates: the Python callbacks through which the plugin pulls prim data on render.

Subclass :class:`SceneDelegate` to serve a scene of your own (a DCC's, a file reader's), or use
:class:`Scene`, which holds prims in memory and is what :meth:`Delegate.insert_prim` fills.
"""

from __future__ import annotations

import dataclasses
from typing import Any, Iterable, Mapping

import numpy as np

from ._abi import Interpolation
from .errors import InvalidArgumentError
from .values import Value, to_matrix, to_value

#: Samples of a world transform: ``[(time, matrix), ...]`` sorted by time (matrices as
#: :func:`~obscura.values.to_matrix` takes them).
TransformSamples = Iterable[tuple[float, Any]]

IDENTITY = np.identity(4).reshape(-1)


class SceneDelegate:
    """The callbacks of ObscuraSceneDelegate, in Python. Every method may raise: the exception is
    logged, kept in :attr:`Delegate.callback_errors` and makes that prim skipped with the message,
    and the render goes on without it.

    Callbacks run on the thread that called :meth:`Delegate.render`: the package never sets
    OBSCURA_SCENE_DELEGATE_THREAD_SAFE, as the GIL would serialise parallel callbacks anyway and a
    value handed out stays valid only until the next callback.
    """

    def get_value(self, path: str, attribute: str, time: float) -> Any:
        """The value of ``attribute`` of the prim at ``path`` at time code ``time``, in any form
        :func:`~obscura.values.to_value` takes, or None when it is not authored (the schema's
        default applies). See ``docs/schemas.md`` for every prim type's attributes."""
        return None

    def get_interpolation(self, path: str, attribute: str) -> Interpolation | None:
        """The interpolation of a primvar or of normals; None for the schema's default."""
        return None

    def sample_transform(self, path: str, time0: float, time1: float, max_samples: int) -> TransformSamples | None:
        """World transforms of the prim over [time0, time1]: at most ``max_samples`` (time, matrix)
        pairs sorted by time, or None for the identity. A prim without animation returns one sample."""
        return None


@dataclasses.dataclass
class Prim:
    """A prim held by :class:`Scene`."""

    type: str
    values: dict[str, Value] = dataclasses.field(default_factory=dict)
    transform: np.ndarray = dataclasses.field(default_factory=lambda: IDENTITY.copy())
    interpolations: dict[str, Interpolation] = dataclasses.field(default_factory=dict)


class Scene(SceneDelegate):
    """An in-memory scene: prims with attribute values converted once, served without copies."""

    def __init__(self) -> None:
        self.prims: dict[str, Prim] = {}

    @staticmethod
    def make_prim(type: str, path: str, values: Mapping[str, Any] | None = None, transform: Any = None,
                  interpolations: Mapping[str, Interpolation] | None = None) -> Prim:
        """A prim with its values converted (raising InvalidArgumentError, naming the attribute)."""
        prim = Prim(type)
        for attribute, value in (values or {}).items():
            prim.values[attribute] = _converted(path, attribute, value)
        if transform is not None:
            prim.transform = _converted_matrix(path, transform)
        prim.interpolations.update(interpolations or {})
        return prim

    def add(self, type: str, path: str, values: Mapping[str, Any] | None = None, transform: Any = None,
            interpolations: Mapping[str, Interpolation] | None = None) -> Prim:
        self.prims[path] = self.make_prim(type, path, values, transform, interpolations)
        return self.prims[path]

    def set(self, path: str, attribute: str, value: Any) -> None:
        """Sets (or, with None, removes) an attribute's value."""
        prim = self.prims[path]
        if value is None:
            prim.values.pop(attribute, None)
        else:
            prim.values[attribute] = _converted(path, attribute, value)

    def set_transform(self, path: str, transform: Any) -> None:
        self.prims[path].transform = _converted_matrix(path, transform)

    def remove(self, path: str) -> None:
        self.prims.pop(path, None)

    def get_value(self, path: str, attribute: str, time: float) -> Value | None:
        prim = self.prims.get(path)
        return prim.values.get(attribute) if prim else None

    def get_interpolation(self, path: str, attribute: str) -> Interpolation | None:
        prim = self.prims.get(path)
        return prim.interpolations.get(attribute) if prim else None

    def sample_transform(self, path: str, time0: float, time1: float, max_samples: int) -> TransformSamples | None:
        prim = self.prims.get(path)
        return [(time0, prim.transform)] if prim else None


def _converted(path: str, attribute: str, value: Any) -> Value:
    try:
        return to_value(value)
    except (ValueError, TypeError) as e:  # numpy's own conversion errors too
        # The conversion's message, with the prim and attribute it belongs to.
        raise InvalidArgumentError(f"{path}: {attribute}: {getattr(e, 'message', e)}") from None


def _converted_matrix(path: str, transform: Any) -> np.ndarray:
    try:
        return to_matrix(transform)
    except (ValueError, TypeError) as e:
        raise InvalidArgumentError(f"{path}: transform: {getattr(e, 'message', e)}") from None
