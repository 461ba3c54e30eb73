"""Inverse kinematics plans, Jacobians and singularity polynomials from constraint ideals."""
