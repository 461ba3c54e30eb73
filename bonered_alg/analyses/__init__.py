"""Further derivation steps a declaration can ask for (``Mechanism.analyses``).

Each analysis is a frozen object with a ``name``, ``check(mechanism)`` (run by the
validator, before any algebra), ``run(derivation, algebra) -> result`` (after the IK/FK
plan) and ``report(result) -> [LaTeX]``:

* :class:`.parasitic.ParasiticMotion`: the coordinates of a platform that the legs fix as
  functions of its free ones (000 eq. 10, 001 eq. 10-12), from a lex basis;
* :class:`.solution_counts.SolutionCounts`: dimension and number of solutions of a closure's
  ideal at rational configurations (004 eq. 18, 28-31);
* :class:`.input_space.InputSpaceSingularities`: singularity factors with the pose
  eliminated, as polynomials in the actuated joints (004 eq. 24-27);
* :class:`.closure_dimension.ClosureDimension`: the Krull dimension of a closure's ideal;
* :class:`.remote_centre.RemoteCentre`: a line of the platform through O, each leg on a
  general platform (002 Sect. 2.4);
* :class:`.pure_translation.PureTranslation`: the platform never turns, each leg on a
  general platform (003 Sect. 2.1).
"""
