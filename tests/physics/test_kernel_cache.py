"""numba's cache of the kernels follows every kernel's source, not only the kernel's own file
(audit.physics.kernel_cache)."""

import importlib
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from numba.core.registry import CPUDispatcher

from audit.physics.kernel_cache import kernel_modules, kernel_sources_digest

REPO = Path(__file__).resolve().parents[2]
KERNEL_MODULES = ("audit.physics.rocking.kernel", "audit.physics.spectrum_kernel",
                  "procedures.iteration_kernels", "procedures.design_spectrum_kernels",
                  "procedures.fixed_point_scan")


def test_every_kernel_is_stamped_with_the_sources_of_all_kernels():
    for name in KERNEL_MODULES:
        importlib.import_module(name)
    kernels = {(name, key): value for name, module in list(sys.modules.items())
               if name.startswith(("audit.", "procedures."))
               for key, value in vars(module).items() if isinstance(value, CPUDispatcher)
               and value.__module__ == name}
    assert len(kernels) >= 40
    for value in kernels.values():
        assert value._cache._cache_file._source_stamp == kernel_sources_digest()
    defining = {Path(sys.modules[name].__file__).resolve() for name, _ in kernels}
    assert defining <= set(kernel_modules())
    assert len(defining) == 10  # floor_motion.py: the building filter's modal recurrences


def _spectrum_probe(tree: Path) -> str:
    """Peaks of one oscillator computed by spectrum_peaks (spectrum_kernel.py, which compiles
    in oscillator.py's step) in a fresh process on ``tree``, its cache in ``tree``'s
    __pycache__."""
    probe = ("import numpy as np; from audit.physics.oscillator import recurrence_coefficients; "
             "from audit.physics.spectrum_kernel import spectrum_peaks; "
             "acc = np.sin(np.arange(400) * 0.05); out = np.empty((1, 3)); "
             "c = recurrence_coefficients(np.array([0.5]), np.array([0.05]), 0.01); "
             "spectrum_peaks(acc, 0.01, c, np.array([2 * np.pi / 0.5]), np.array([0.05]), "
             "False, False, out); print(repr(out[0, 0]))")
    done = subprocess.run([sys.executable, "-c", probe], cwd=tree, capture_output=True,
                          text=True, check=True, env={"PATH": "/usr/bin:/bin"})
    return done.stdout.strip()


@pytest.mark.slow  # ~25 s: compiles kernels afresh
def test_a_change_to_a_called_kernel_in_another_file_recompiles_its_caller(tmp_path):
    """numba alone would reuse spectrum_peaks' cached machine code, with the old step of
    oscillator.py compiled in, after a change to oscillator.py only."""
    tree = tmp_path / "tree"
    for package in ("audit", "procedures", "records", "reports"):  # import audit checks all four
        shutil.copytree(REPO / package, tree / package,
                        ignore=shutil.ignore_patterns("__pycache__"))
    first = _spectrum_probe(tree)
    assert _spectrum_probe(tree) == first  # cached, and the same
    oscillator = tree / "audit" / "physics" / "oscillator.py"
    text = oscillator.read_text()
    step = "return (c[0] * u + c[1] * v"
    assert step in text
    oscillator.write_text(text.replace(step, "return (2.0 * c[0] * u + c[1] * v"))
    assert _spectrum_probe(tree) != first
