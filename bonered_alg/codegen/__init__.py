"""Code generation: symbolic results -> plain numpy modules in ``generated/``."""
