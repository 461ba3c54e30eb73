"""Study-parameter (dual quaternion) algebra: one convention, symbolic and numeric."""
