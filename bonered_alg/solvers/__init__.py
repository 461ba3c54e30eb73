"""Solvers in registries: each recognizes its case, certifies it, derives, and (for the
forward kinematics) emits the kernels of its runtime step.

* :mod:`.legs`: the ideal of one leg: a certified closed form (a distance leg) or a
  Groebner elimination;
* :mod:`.closures`: the forward kinematics of one closure: the eliminant of a 3-RPS closure
  or the back-substitution through a triangular lex basis.
"""
