"""Workspace analysis from the generated modules: grids, membership, chunked and parallel
scans, coordinate ranges by boundary search, paths and plots.  Generic: it reads the
generated modules only, and imports neither sympy nor the report (the papers' comparisons
with the Stewart platform are ``bonered_alg.studies.bone_reduction``)."""
