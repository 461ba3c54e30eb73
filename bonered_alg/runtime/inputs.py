"""Checks of the arguments of generated functions: clear errors naming the mechanism."""

from __future__ import annotations

import numpy


def parameters(model, func: str, params: dict) -> list:
    """The geometric parameters in ``model.parameters`` order, keywords overriding defaults."""
    unknown = sorted(set(params) - set(model.parameters))
    if unknown:
        raise TypeError(f"{model.mechanism}.{func}: unknown geometric parameter(s) {unknown}; "
                        f"expected some of {list(model.parameters)}")
    out = []
    for name, default in model.parameters.items():
        value = params.get(name, default)
        if value is None:
            raise ValueError(
                f"{model.mechanism}.{func}: geometric parameter {name!r} has no value "
                f"({model.parameter_notes[name]}); pass {name}=<value in "
                f"{model.parameter_units[name]}>")
        value = numpy.asarray(value, dtype=float)
        if not numpy.all(numpy.isfinite(value)):
            raise ValueError(f"{model.mechanism}.{func}: geometric parameter {name!r} is not "
                             "finite")
        out.append(value)
    return out


def coordinates(model, func: str, values, names, what: str) -> numpy.ndarray:
    """``values`` as a float array of shape (..., len(names))."""
    p = numpy.asarray(values, dtype=float)
    if p.ndim == 0 or p.shape[-1] != len(names):
        raise ValueError(f"{model.mechanism}.{func}: {what} must have shape (..., {len(names)}) "
                         f"with coordinates {tuple(names)}, got shape {p.shape}")
    return p


def pose(model, func: str, value) -> numpy.ndarray:
    return coordinates(model, func, value, model.pose, "pose")


def joints(model, func: str, q, shape) -> numpy.ndarray:
    q = coordinates(model, func, q, model.joints, "joints")
    return numpy.broadcast_to(q, shape + (len(model.joints),))


def mode(model, func: str, value, count: int | None = None, table: str = "MODE_BITS") -> int:
    count = model.modes if count is None else count
    if not isinstance(value, (int, numpy.integer)) or not 0 <= int(value) < count:
        raise ValueError(f"{model.mechanism}.{func}: mode must be an integer in [0, {count}), "
                         f"got {value!r}; see {table}")
    return int(value)


def columns(a: numpy.ndarray) -> list:
    """The last axis of ``a`` as a list of arrays (the kernels take one argument each)."""
    return [a[..., i] for i in range(a.shape[-1])]


def stacked(values, shape) -> numpy.ndarray:
    """Kernel outputs (scalars or arrays) broadcast to ``shape`` and stacked on a last axis."""
    return numpy.stack([numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)
                        for v in values], axis=-1)
