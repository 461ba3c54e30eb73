"""Joints, legs and mechanisms: the input side of the pipeline."""
