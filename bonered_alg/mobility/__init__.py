"""Mobility by screw theory (003 Sect. 2.1): joint screws, constraint-wrench systems, the
order of a mechanism, redundant constraints and the modified Kutzbach-Grubler count."""
