"""Helpers shared by scripts/throughput and scripts/profile-stages (Python 3 standard library
only): GLB variants for the peer comparison (glb), the mean of an EXR image (exr), the machine
and its load (machine)."""
