"""Mechanism declarations, one module each (``MECHANISM = declare(...)``); the registry of
the mechanisms ``make derive`` derives is ``bonered_alg.registry``."""
