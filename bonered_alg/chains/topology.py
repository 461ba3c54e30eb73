"""The body/joint graph of a mechanism, derived from its legs, and its mobility count.

Each leg runs from the body it stands on (its closure's ``base``) through one body per joint
to the closure's ``point``; offsets move along a body and create none.  A closure's
couplings add the joints of the linkages they stand for.  The Kutzbach-Gruebler count is
taken per closure with the closure's own ``lambda`` (3 for planar loops, 6 for spatial
ones), since one global formula over-counts the constraints of planar loops.
"""

from __future__ import annotations

from dataclasses import dataclass

import networkx as nx

from .joints import JOINT_DOF


@dataclass(frozen=True)
class MobilityCount:
    """``lambda (n - 1 - j) + sum f - c`` for one closure's subsystem."""

    closure: str
    lam: int
    bodies: int
    joints: int
    freedoms: int
    extra_constraints: int
    note: str

    @property
    def mobility(self) -> int:
        return self.lam * (self.bodies - 1 - self.joints) + self.freedoms - self.extra_constraints

    def formula(self) -> str:
        return (f"{self.lam}({self.bodies} - 1 - {self.joints}) + {self.freedoms} - "
                f"{self.extra_constraints} = {self.mobility}")


def closure_edges(closure) -> list[tuple[str, str, str, str]]:
    """``(body, body, joint kind, label)`` for every joint of ``closure``'s legs and couplings."""
    edges = []
    for leg in closure.legs:
        body = leg.base or closure.base
        moving = [j for j in leg.joints if j.kind != "offset"]
        for k, j in enumerate(moving):
            nxt = closure.point if k == len(moving) - 1 else f"{leg.name}.{k + 1}"
            edges.append((body, nxt, j.kind, j.label))
            body = nxt
    for cp in closure.couplings:
        edges.extend(cp.linkage)
    return edges


def topology(closures) -> nx.MultiGraph:
    """The body/joint multigraph of all ``closures``."""
    g = nx.MultiGraph()
    for closure in closures:
        for a, b, kind, label in closure_edges(closure):
            g.add_edge(a, b, joint=kind, label=label, closure=closure.name)
    return g


def loops(graph: nx.MultiGraph) -> list[list[str]]:
    """Independent loops (a cycle basis of the body/joint graph, parallel joints included)."""
    simple = nx.Graph()
    out: list[list[str]] = []
    for a, b, _key in graph.edges(keys=True):
        if simple.has_edge(a, b):
            out.append(sorted([a, b]))
        else:
            simple.add_edge(a, b)
    root = "base" if "base" in simple else None
    out.extend(sorted(sorted(c) for c in nx.cycle_basis(simple, root=root)))
    return out


def mobility_counts(closures) -> list[MobilityCount]:
    """The Kutzbach-Gruebler count of each closure that is not driven by other closures."""
    out = []
    for closure in closures:
        if closure.driven:
            continue
        edges = closure_edges(closure)
        bodies = {x for a, b, _, _ in edges for x in (a, b)}
        out.append(MobilityCount(closure.name, closure.lam, len(bodies), len(edges),
                                 sum(JOINT_DOF[k] for _, _, k, _ in edges),
                                 closure.extra_constraints, closure.constraints_note))
    return out
