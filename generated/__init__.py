"""Generated numeric modules (``make derive``); import as ``bonered_alg.generated.<name>``.

Never edit these files by hand: they are rewritten from ``bonered_alg/mechanisms/``.
"""
