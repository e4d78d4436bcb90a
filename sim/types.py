"""Type aliases shared across sim/."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

FloatArray = npt.NDArray[np.float64]
FloatsLike = Sequence[float] | FloatArray
"""Anything indexable as floats: a tuple, a list, or a 1-D numpy array."""
