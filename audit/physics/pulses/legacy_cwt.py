"""MATLAB's legacy continuous wavelet transform ``cwt(signal, scales, wname)`` for an orthogonal
wavelet, the transform Shahi & Baker's (2014) MATLAB classifies with.

PyWavelets' own :func:`pywt.cwt` takes only continuous wavelet families and refuses 'db4', so the
transform is written here. It is the legacy algorithm: the wavelet ψ (cascade of
``precision`` iterations) integrated, Ψ(x) = Σ ψ·Δx, resampled at each scale a on the signal's
sample grid, convolved with the signal and differenced, C(a, b) = −√a · Δ[s ∗ Ψ(·/a)] (b),
the central n samples kept. Differencing the convolution with the integrated wavelet is the
convolution with the wavelet itself to the order of Δx, so C(a, b) ≈ (1/√a) Σ_k s_k ψ((k−b)/a)
(the direct sum the test compares it against).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pywt
from scipy.signal import fftconvolve

#: Cascade iterations of the wavelet function MATLAB's cwt uses (its ``precis``).
PRECISION = 10


@lru_cache(maxsize=4)
def integrated_wavelet(wavelet: str = "db4", precision: int = PRECISION):
    """(Ψ, x): the running integral of ψ on its cascade grid x (starting at 0)."""
    _, psi, x = pywt.Wavelet(wavelet).wavefun(level=precision)
    return np.cumsum(psi) * (x[1] - x[0]), x - x[0]


def legacy_cwt(signal, scales, wavelet: str = "db4") -> np.ndarray:
    """Coefficients C[scale, sample] of MATLAB's legacy ``cwt`` [signal units × √sample].

    Parameters
    ----------
    signal : array_like
        Samples s_k (unit step: scales are in samples).
    scales : array_like of float
        Scales a ≥ 1 [samples].
    wavelet : str
        An orthogonal PyWavelets wavelet with a cascade function ('db4').

    Returns
    -------
    numpy.ndarray
        Shape (len(scales), len(signal)).
    """
    signal = np.asarray(signal, dtype=float)
    psi_integral, x = integrated_wavelet(wavelet)
    step, x_max = x[1], x[-1]
    n = signal.size
    coefficients = np.empty((len(scales), n))
    for row, scale in enumerate(np.asarray(scales, dtype=float)):
        # Ψ at the sample points 0, 1, ..., a·x_max of the dilated wavelet (floor indexing)
        index = np.floor(np.arange(np.floor(scale * x_max) + 1) / (scale * step)).astype(int)
        if index.size == 1:
            index = np.array([0, 0])
        full = np.diff(fftconvolve(signal, psi_integral[index][::-1]))
        first = (full.size - n) // 2
        coefficients[row] = -np.sqrt(scale) * full[first:first + n]
    return coefficients
