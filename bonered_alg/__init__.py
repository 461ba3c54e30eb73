"""bonered_alg: algebraic kinematics of surgical parallel mechanisms.

Importing this package is cheap and does not import sympy, so that the generated
numeric modules (``bonered_alg.generated.<name>``) work where sympy is absent.
"""

__version__ = "0.1.0"
