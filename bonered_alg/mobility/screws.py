"""Screw systems and the modified Kutzbach-Grubler count (003 eq. 1-6; Huang, Zhao and
Zhao, Advanced Spatial Mechanism, 2006, the paper's ref. [25]).

Screws are Plucker ray coordinates ``(s; s0)``: a revolute joint about the unit axis ``s``
through ``r`` is ``(s; r x s)``, a helical one of pitch ``h`` ``(s; r x s + h s)``, a
prismatic one ``(0; s)``; a force along a line is ``(f; r x f)``, a couple ``(0; m)``: the
toolkit's twist ``(omega; v)``, with ``v`` the velocity of the body point at the origin.
Two screws are reciprocal when ``s1 . s0_2 + s2 . s0_1 = 0`` (a wrench that does no work
on the twist).

* each chain's twist system ``T_i`` (its joint screws at one configuration) and its
  constraint system ``W_i``, the screws reciprocal to ``T_i`` (003 eq. 4);
* common constraints: the screws reciprocal to every joint screw of every chain; their
  number ``lambda`` gives the order ``d = 6 - lambda`` (003: the couple about Y, d = 5);
* redundant constraints: ``v = sum_i (dim W_i - lambda) - (dim sum_i W_i - lambda)``;
* local freedoms: ``sum_i (f_i - rank T_i)``, joint rates of a chain that move no body
  beyond it (a spin of a link between two spherical joints);
* ``M = d (n - g - 1) + sum f + v - local`` (003 eq. 2);
* the platform's twist space: the screws reciprocal to every ``W_i``; its dimension is the
  instantaneous mobility of the platform and its angular part says whether it only
  translates (003 Sect. 2.1, last paragraph).

The ranks are numeric (singular values above ``RANK_RTOL`` of the largest), at one
configuration: a generic one gives the generic counts, a singular one shows its loss.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

RANK_RTOL = 1e-9
# the reciprocal product as a bilinear form: w . DELTA . t = s_w . s0_t + s_t . s0_w
DELTA = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])


def revolute(axis, point, pitch: float = 0.0) -> np.ndarray:
    """``(s; r x s + h s)`` for the unit axis ``s`` through ``point`` (pitch ``h``)."""
    s = np.asarray(axis, dtype=float)
    s = s / np.linalg.norm(s)
    return np.concatenate([s, np.cross(np.asarray(point, dtype=float), s) + pitch * s])


def prismatic(axis) -> np.ndarray:
    """``(0; s)``: a translation along the unit direction ``s``."""
    s = np.asarray(axis, dtype=float)
    return np.concatenate([np.zeros(3), s / np.linalg.norm(s)])


def reciprocal_product(a, b) -> float:
    """``s_a . s0_b + s_b . s0_a`` (zero: the wrench ``a`` does no work on the twist
    ``b``)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(a @ DELTA @ b)


def _scaled(screws) -> tuple[np.ndarray, float]:
    """The rows with their moment parts divided by a length scale ``L`` (the largest moment
    over the largest direction), so that rank decisions do not depend on the unit of
    length; reciprocity is unchanged (the product scales by 1/L)."""
    m = np.atleast_2d(np.asarray(screws, dtype=float)).reshape(-1, 6)
    if not m.size:
        return m, 1.0
    big = float(np.abs(m[:, 3:]).max())
    small = float(np.abs(m[:, :3]).max())
    if small <= RANK_RTOL * big:  # couples or translations only
        scale = big if big > 0 else 1.0
    else:
        scale = big / small if big > small else 1.0
    return np.hstack([m[:, :3], m[:, 3:] / scale]), scale


def _kept(sv: np.ndarray) -> int:
    return int((sv > RANK_RTOL * sv[0]).sum()) if sv.size and sv[0] > 0 else 0


def rank(screws) -> int:
    """Numeric rank of a screw system (rows)."""
    scaled, _ = _scaled(screws)
    return _kept(np.linalg.svd(scaled, compute_uv=False)) if scaled.size else 0


def reciprocal(screws) -> np.ndarray:
    """A basis (rows) of the screws reciprocal to every row of ``screws``: the null space
    of ``screws . DELTA`` (003 eq. 4 from eq. 3)."""
    scaled, scale = _scaled(screws)
    if not scaled.size:
        return np.eye(6)
    _, sv, vt = np.linalg.svd(scaled @ DELTA)
    basis = vt[_kept(sv):]
    basis = np.hstack([basis[:, :3], basis[:, 3:] * scale])
    return basis / np.linalg.norm(basis, axis=1, keepdims=True)


@dataclass(frozen=True)
class ChainScrews:
    """One chain between base and platform: its joint screws (rows), the number of its
    joints, and their freedoms (a spherical joint: one joint, three freedoms)."""

    name: str
    screws: np.ndarray
    joints: int
    freedoms: int | None = None  # sum of the joints' freedoms (None: one per screw)

    @property
    def dof(self) -> int:
        return len(np.atleast_2d(self.screws)) if self.freedoms is None else self.freedoms


@dataclass(frozen=True)
class Mobility:
    """The counts of 003 eq. (2) and the platform's twist space."""

    chains: tuple[str, ...]
    twist_ranks: tuple[int, ...]  # rank T_i
    constraint_dims: tuple[int, ...]  # dim W_i = 6 - rank T_i
    common: np.ndarray  # basis of the common constraints (rows)
    order: int  # d = 6 - lambda
    redundant: int  # v
    local: int  # local freedoms
    links: int  # n, base and platform included
    joints: int  # g
    freedoms: int  # sum f
    platform: np.ndarray  # basis of the platform's twists (rows)

    @property
    def kutzbach_grubler(self) -> int:
        """003 eq. (2): ``M = d (n - g - 1) + sum f + v - local``."""
        return self.order * (self.links - self.joints - 1) + self.freedoms + self.redundant \
            - self.local

    @property
    def platform_dimension(self) -> int:
        return len(self.platform)

    @property
    def rotational_dimension(self) -> int:
        """Dimension of the angular parts of the platform's twists (unit rows: singular
        values above RANK_RTOL count)."""
        if not len(self.platform):
            return 0
        sv = np.linalg.svd(self.platform[:, :3], compute_uv=False)
        return int((sv > RANK_RTOL).sum())

    @property
    def translational(self) -> bool:
        """The platform only translates (003: pure translation)."""
        return bool(len(self.platform)) and self.rotational_dimension == 0


def mobility(chains: Sequence[ChainScrews]) -> Mobility:
    """003 eq. (2)-(6) for a parallel mechanism: each chain a serial chain from the base to
    the platform (so n = 2 + sum (g_i - 1) links, g = sum g_i joints)."""
    if not chains:
        raise ValueError("mobility needs at least one chain")
    for c in chains:
        s = np.asarray(c.screws, dtype=float)
        if s.ndim != 2 or s.shape[1] != 6 or not np.isfinite(s).all():
            raise ValueError(f"chain {c.name!r}: expected finite joint screws of shape (k, 6), "
                             f"got {s.shape}")
    ranks = tuple(rank(c.screws) for c in chains)
    constraints = [reciprocal(c.screws) for c in chains]
    everything = np.vstack([np.asarray(c.screws, dtype=float) for c in chains])
    common = reciprocal(everything)
    lam = len(common)
    dims = tuple(len(w) for w in constraints)
    all_w = np.vstack(constraints) if any(dims) else np.zeros((0, 6))
    total = rank(all_w)
    redundant = sum(k - lam for k in dims) - (total - lam)
    freedoms = sum(c.dof for c in chains)
    local = sum(c.dof - r for c, r in zip(chains, ranks))
    joints = sum(c.joints for c in chains)
    links = 2 + sum(c.joints - 1 for c in chains)
    platform = reciprocal(all_w) if total else np.eye(6)
    return Mobility(tuple(c.name for c in chains), ranks, dims, common, 6 - lam, redundant,
                    local, links, joints, freedoms, platform)
