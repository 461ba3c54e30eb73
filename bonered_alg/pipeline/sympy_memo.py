"""Two of sympy's structural functions remembered for a derivation: the same results in
less time.

sympy recomputes both on every call by walking the whole subtree, and the deep expressions
of a derivation make the walks quadratic:

* ``sympy.core.sorting._node_count``, the first key of ``sympy.ordered``, which ``cse``
  applies to the arguments of every Add and Mul it rebuilds (a third of tripod_planar's
  code generation, measured with cProfile);
* ``Basic.free_symbols``, which ``diff`` asks of every term it differentiates (a quarter
  of the Jacobian kernels' derivatives).

Both are pure functions of the expression (equal expressions are the same tree), so within
the block they are remembered: every ordering, derivative and output is the one sympy
computes without it.  ``free_symbols`` is remembered for the classes that use ``Basic``'s
own rule (the union over the arguments) and handed out as a new set each time, as sympy
does (callers may change it).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager


@contextmanager
def remembered_structure() -> Iterator[None]:
    """Within the block, ``_node_count`` and ``Basic.free_symbols`` keep their values (new
    dicts per block); sympy's own functions are restored afterwards.  Where sympy lacks
    the private ``_node_count`` (another version), only ``free_symbols`` is remembered."""
    from sympy.core import sorting
    from sympy.core.basic import Basic

    node_original = getattr(sorting, "_node_count", None)
    free_original = Basic.__dict__["free_symbols"]
    counts: dict = {}
    symbols: dict = {}

    def node_count(e):
        # sympy's rule: a Float counts 1/2, any other node 1 plus its arguments' counts
        if e.is_Float:
            return 0.5
        if not e.args:
            return 1
        n = counts.get(e)
        if n is None:
            n = counts[e] = 1 + sum(map(node_count, e.args))
        return n

    def free_symbols(self):
        # Basic's rule, the union of the arguments' free symbols, kept per expression
        if not self.args:
            return set()
        found = symbols.get(self)
        if found is None:
            found = symbols[self] = frozenset().union(*(a.free_symbols for a in self.args))
        return set(found)

    if node_original is not None:
        sorting._node_count = node_count
    Basic.free_symbols = property(free_symbols, doc=free_original.__doc__)
    try:
        yield
    finally:
        Basic.free_symbols = free_original
        if node_original is not None:
            sorting._node_count = node_original
