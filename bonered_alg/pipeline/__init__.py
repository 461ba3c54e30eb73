"""The derivation pipeline: declaration -> ideals -> plan -> analyses -> generated module ->
studies and paper checks -> report and records.

:mod:`.stages` holds the stages, :mod:`.results` the immutable results they hand on,
:mod:`.runner` runs them (``derive`` one mechanism in memory, ``derive_all`` every
registered one that is out of date), :mod:`.outputs` renders and writes the files and
:mod:`.provenance` computes the derivation hash.  (This package module imports nothing, so
that a derivation's import graph stays free of the runner and its registry.)
"""
