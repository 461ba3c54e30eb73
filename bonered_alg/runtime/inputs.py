"""Checks of the arguments of generated functions: clear errors naming the mechanism."""

from __future__ import annotations

import math
import operator

import numpy


def _numeric(model, func: str, value, what: str) -> numpy.ndarray:
    """``value`` as a float array; strings, objects, complex numbers and booleans are a
    TypeError naming the mechanism, the function and the argument."""
    try:
        raw = numpy.asarray(value)
    except (TypeError, ValueError) as exc:  # ragged nested sequences
        raise TypeError(f"{model.mechanism}.{func}: {what} must be a real number or an "
                        f"array of real numbers, got {type(value).__name__} ({exc})") from None
    if raw.dtype.kind not in "iuf":
        kind = {"U": "strings", "S": "bytes", "O": "Python objects", "c": "complex numbers",
                "b": "booleans"}.get(raw.dtype.kind, f"dtype {raw.dtype}")
        raise TypeError(f"{model.mechanism}.{func}: {what} must be real numbers (float or "
                        f"int), got an array of {kind}")
    return raw.astype(float, copy=False)


DOMAIN_TEST = {"positive": (lambda v: v > 0, "> 0"),
               "nonnegative": (lambda v: v >= 0, ">= 0")}


# scalars checked with float comparisons (bool, a subclass of int, fails the exact type
# test and goes through _numeric, which rejects it)
_PLAIN_SCALARS = (float, int, numpy.float64)
# id(model) -> (model, its checked default parameters, the default values they were checked
# from): checked once per model and defaults (the model kept, so that its id is not reused
# while the entry lives)
_DEFAULTS: dict[int, tuple] = {}
# id(model) -> (model, keyword names, their values, the checked parameters, the defaults
# then): the last keywords checked per model, where every value is a plain scalar
_KEYWORDS: dict[int, tuple] = {}


class Parameters(list):
    """:func:`parameters`' result: the checked values in ``model.parameters`` order, and
    ``vector``, the same numbers as a float64 array where every value is a scalar (what
    the compiled fast path takes), else None."""

    __slots__ = ("vector",)

    def __init__(self, values, vector=None):
        super().__init__(values)
        self.vector = vector

    @classmethod
    def of(cls, values: list) -> Parameters:
        scalar = all(v.ndim == 0 for v in values)
        vector = numpy.array([float(v) for v in values]) if scalar else None
        if vector is not None:
            vector.flags.writeable = False
        return cls(values, vector)


def _same_objects(values: tuple, mapping) -> bool:
    """True where ``mapping``'s values are the objects ``values``, in order."""
    return len(values) == len(mapping) and all(map(operator.is_, values, mapping.values()))


def parameters(model, func: str, params: dict) -> Parameters:
    """The geometric parameters in ``model.parameters`` order, keywords overriding defaults;
    each finite and within its domain (``model.parameter_domains``: a length is > 0).

    A plain scalar (float, int, numpy.float64) within its domain is checked with float
    comparisons (on one pose the array checks cost several times the kinematics); anything
    else, and any scalar that fails, takes the array checks and their errors.  The defaults
    are checked once per model, and the last plain-scalar keywords once while each value is
    the same object.  A scalar is passed on as a ``numpy.float64``, not a 0-d
    array: the same IEEE arithmetic (and infinity, not an exception, on a division by
    zero), and a kernel's arithmetic on parameters alone costs about 50 ns an operation
    instead of about 400 (measured with numpy 2 on this project's machine)."""
    if not params:
        known = _DEFAULTS.get(id(model))
        if known is not None and known[0] is model and _same_objects(known[2], model.parameters):
            return Parameters(known[1], known[1].vector)
    else:
        known = _KEYWORDS.get(id(model))
        if (known is not None and known[0] is model and known[1] == tuple(params)
                and _same_objects(known[2], params) and _same_objects(known[4], model.parameters)):
            return Parameters(known[3], known[3].vector)
        unknown = sorted(set(params) - set(model.parameters))
        if unknown:
            raise TypeError(f"{model.mechanism}.{func}: unknown geometric parameter(s) "
                            f"{unknown}; expected some of {list(model.parameters)}")
    domains = model.parameter_domains or {}
    out = []
    for name, default in model.parameters.items():
        value = params.get(name, default) if params else default
        if type(value) in _PLAIN_SCALARS:
            try:
                v = float(value)
            except OverflowError:  # an int beyond floats: the array checks say so
                v = math.nan
            test = DOMAIN_TEST.get(domains.get(name, "real"))
            if math.isfinite(v) and (test is None or test[0](v)):
                out.append(numpy.float64(v))
                continue
        if value is None:
            raise ValueError(
                f"{model.mechanism}.{func}: geometric parameter {name!r} has no value "
                f"({model.parameter_notes[name]}); pass {name}=<value in "
                f"{model.parameter_units[name]}>")
        value = _numeric(model, func, value, f"geometric parameter {name!r}")
        if not numpy.all(numpy.isfinite(value)):
            raise ValueError(f"{model.mechanism}.{func}: geometric parameter {name!r} is not "
                             "finite")
        domain = domains.get(name, "real")
        if domain in DOMAIN_TEST:
            test, text = DOMAIN_TEST[domain]
            if not numpy.all(test(value)):
                raise ValueError(f"{model.mechanism}.{func}: geometric parameter {name!r} "
                                 f"must be {text} ({model.parameter_notes[name]}), got "
                                 f"{value if value.ndim == 0 else value[~test(value)][:3]}"
                                 f" {model.parameter_units[name]}")
        out.append(value[()] if value.ndim == 0 else value)  # a 0-d array as a float64
    out = Parameters.of(out)
    if not params:  # the defaults passed: the same values while the defaults stay the
        # same objects (a module's PARAMETERS dict assigned a new value is checked again)
        _DEFAULTS[id(model)] = (model, out, tuple(model.parameters.values()))
    elif all(type(v) in _PLAIN_SCALARS for v in params.values()):
        # keywords of immutable scalars: the same objects again (a control loop passing
        # its geometry on every call) give the same values; anything else is checked again
        _KEYWORDS[id(model)] = (model, tuple(params), tuple(params.values()), out,
                                tuple(model.parameters.values()))
    return Parameters(out, out.vector)


def coordinates(model, func: str, values, names, what: str) -> numpy.ndarray:
    """``values`` as a float array of shape (..., len(names))."""
    p = _numeric(model, func, values, what)
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
    if (not isinstance(value, (int, numpy.integer)) or isinstance(value, bool)
            or not 0 <= int(value) < count):
        raise ValueError(f"{model.mechanism}.{func}: mode must be an integer in [0, {count}), "
                         f"got {value!r}; see {table}")
    return int(value)


def flag(model, func: str, name: str, value) -> bool:
    """A boolean keyword (``limits``): True or False only, so that ``limits='no'`` is an
    error rather than true."""
    if not isinstance(value, (bool, numpy.bool_)):
        raise TypeError(f"{model.mechanism}.{func}: {name} must be True or False, got "
                        f"{value!r}")
    return bool(value)


def columns(a: numpy.ndarray) -> list:
    """The last axis of ``a`` as a list of arrays (the kernels take one argument each)."""
    return [a[..., i] for i in range(a.shape[-1])]


def contiguous_columns(a: numpy.ndarray) -> list:
    """:func:`columns`, each a contiguous copy (numpy's loops are about 1.7 times slower on
    strided arrays: worth it for a kernel that reads its arguments many times)."""
    return [contiguous(a[..., i]) for i in range(a.shape[-1])]


def rows_last(a: numpy.ndarray) -> numpy.ndarray:
    """``numpy.moveaxis(a, 0, -1)``: a view with the first axis last (one row per unknown
    becomes one column per unknown), without moveaxis' argument normalization (about 7
    microseconds a call, paid on every chunk)."""
    return a.transpose((*range(1, a.ndim), 0))


def contiguous(a: numpy.ndarray) -> numpy.ndarray:
    """``a``, copied where it is not C-contiguous; its shape kept (0-d included, which
    ``numpy.ascontiguousarray`` turns into shape (1,))."""
    return a if a.flags.c_contiguous else numpy.array(a)


def broadcast(v, shape) -> numpy.ndarray:
    """``numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)``, or ``v`` itself where it
    is a float array of that shape already (broadcast_to costs about 2 us a call, paid for
    every kernel output: hundreds of times in one forward kinematics call).  For values
    used at once (stacked, compared): the result may be ``v``, writable."""
    if type(v) is numpy.ndarray and v.shape == shape and v.dtype == numpy.float64:
        return v
    return numpy.broadcast_to(numpy.asarray(v, dtype=float), shape)


def against_modes(par) -> list:
    """The parameters, those given per configuration (arrays of the configurations'
    shape) with an axis after it, against which the modes' axis broadcasts (forward
    kinematics: the modes of a back-substitution, an eliminant's roots)."""
    return [p if numpy.ndim(p) == 0 else numpy.asarray(p)[..., None] for p in par]


def stacked(values, shape) -> numpy.ndarray:
    """Kernel outputs (scalars or arrays) broadcast to ``shape`` and stacked on a last axis."""
    return numpy.stack([broadcast(v, shape) for v in values], axis=-1)
