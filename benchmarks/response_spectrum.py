"""Speed and accuracy of the response-spectrum recurrence against a loop of scipy.signal.lsim.

Sd, Sv, Sa for 200 periods × 6 dampings on the seed record with the most samples, against
``scipy.signal.lsim`` (first-order hold, the same piecewise-linear excitation) per oscillator.

    ROCKING_AUDIT_RECORDS=../shared/records/seed-suite.toml python benchmarks/response_spectrum.py
"""

import math
import time

import numpy as np
from scipy import signal

from audit.physics.oscillator import response_spectra
from records import load_records


def main():
    motions = [entry.motion for entry in load_records() if entry.motion is not None]
    motion = max(motions, key=lambda m: m.acceleration.size)
    periods = np.linspace(0.05, 10.0, 200)
    dampings = np.array([0.02, 0.05, 0.10, 0.15, 0.20, 0.30])
    response_spectra(motion, periods[:2], dampings[:1])  # compile outside the timing
    start = time.perf_counter()
    spectra = response_spectra(motion, periods, dampings)
    ours = time.perf_counter() - start

    start = time.perf_counter()
    worst = {"sd": 0.0, "sv": 0.0, "sa": 0.0}
    for j, xi in enumerate(dampings):
        for i, period in enumerate(periods):
            w = 2 * math.pi / period
            system = signal.lti([[0, 1], [-w * w, -2 * xi * w]], [[0], [1]], [[1, 0], [0, 1]],
                                [[0], [0]])
            _, y, _ = signal.lsim(system, -motion.acceleration, motion.time, interp=True)
            u, v = y[:, 0], y[:, 1]
            reference = {"sd": np.max(np.abs(u)), "sv": np.max(np.abs(v)),
                         "sa": np.max(np.abs(2 * xi * w * v + w * w * u))}
            for key, value in reference.items():
                worst[key] = max(worst[key], abs(getattr(spectra, key)[j, i] / value - 1))
    loop = time.perf_counter() - start
    print(f"record {motion.id}: {motion.acceleration.size} samples at dt = {motion.dt} s")
    print(f"response_spectra: {ours:.3f} s for {periods.size} periods × {dampings.size} dampings")
    print(f"lsim loop:        {loop:.2f} s")
    print(f"speed ratio:      {loop / ours:.0f}x")
    print("largest relative difference: " + ", ".join(f"{k} {v:.1e}" for k, v in worst.items()))


if __name__ == "__main__":
    main()
