"""The driver's heap policy (audit/engine/shared/heap.py), checked against what glibc itself reports."""

import ctypes
import os
import subprocess
import sys

import pytest

try:
    ctypes.CDLL(None).malloc_info
except AttributeError:
    pytest.skip("the C library is not glibc", allow_module_level=True)

# A thread mallocs after the policy is (or is not) set; glibc's malloc_info then lists one
# <heap nr=...> per arena in use.
HEAPS_AFTER_A_THREAD_ALLOCATES = """
import ctypes, sys, threading
from audit.engine.shared.heap import return_freed_memory_promptly
libc = ctypes.CDLL(None)
libc.malloc.restype = libc.fopen.restype = ctypes.c_void_p
libc.malloc_info.argtypes = [ctypes.c_int, ctypes.c_void_p]
libc.fclose.argtypes = [ctypes.c_void_p]
if sys.argv[1] == "policy":
    assert return_freed_memory_promptly()
thread = threading.Thread(target=lambda: [libc.malloc(4096) for _ in range(64)])
thread.start(); thread.join()
out = libc.fopen(sys.argv[2].encode(), b"w")
libc.malloc_info(0, out)
libc.fclose(out)
"""


@pytest.mark.parametrize("policy, heaps", [("policy", 1), ("default", 2)])
def test_threads_share_one_arena_once_the_policy_is_set(tmp_path, policy, heaps):
    report = tmp_path / "malloc_info.xml"
    environ = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_ARENA")}
    subprocess.run([sys.executable, "-c", HEAPS_AFTER_A_THREAD_ALLOCATES, policy, str(report)],
                   check=True, env=environ)
    assert report.read_text().count("<heap nr=") == heaps
