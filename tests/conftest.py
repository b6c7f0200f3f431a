"""Shared pytest configuration for flexsim's tests."""

import os

# Small dense linear algebra does not benefit from BLAS threads and suffers from oversubscription
# (see docs/performance.md, "BLAS threads"); pin before numpy is imported by the tests.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MPLBACKEND", "Agg")
