"""The numeric environment controller code runs in: one BLAS kernel, one thread, one numpy SIMD level.

Why: numpy hands `u @ v`, `T @ p` and `np.linalg.solve` to OpenBLAS, which picks its kernel by CPU, and
numpy itself picks its SIMD loops by CPU (on AVX-512, Intel's SVML for `np.arctan2`, `np.exp`, ...). The
kernels round differently in the last bit: under AVX-512 a dot product is fused, under Haswell it is not.
A closed loop amplifies one bit into another run, and a verdict near its threshold flips. So before numpy
loads, wherever controller code runs (the sandbox worker, `simiam run`, the tests, the benchmarks), the
project sets:

- ``OPENBLAS_CORETYPE=Haswell`` where the CPU has AVX2 and FMA: the kernel the original's recordings agree
  with (its matrix products fused, its dot products not). Without AVX2/FMA the stated fallback is
  ``Nehalem`` (no fused operations): runs there can differ from official grading in the last digits.
- one BLAS thread (``OPENBLAS_NUM_THREADS=1`` and the others): a threaded sum splits in another order.
- ``NPY_DISABLE_CPU_FEATURES`` = numpy's AVX-512 targets: its loops stay at the AVX2 level every
  x86-64-v3 CPU runs, where `np.arctan2`, `np.exp`, `np.log` give the C library's results.

``describe()`` reads back what really loaded (OpenBLAS's own kernel name, numpy's enabled targets); every
result and trace records it, and says plainly where nothing could be pinned (numpy on Apple's Accelerate,
on ARM, or numpy imported before simiam).

``SIMIAM_BLAS_KERNEL`` chooses another kernel (tests prove that verdicts have a margin by grading under
every kernel the CPU runs): a kernel name sets that kernel (numpy's SIMD level stays pinned); ``native``
pins nothing at all (the CPU's own kernel and numpy's own loops).

Standard library only: the sandbox worker imports it (grader.sandbox.exposed) to report its environment.
"""

from __future__ import annotations

import os
import sys
import warnings

OFFICIAL_KERNEL = "Haswell"   # the golden traces agree with it; needs AVX2 and FMA
FALLBACK_KERNEL = "Nehalem"   # older x86-64 CPUs: no fused operations anywhere (needs SSE4.2)
OVERRIDE = "SIMIAM_BLAS_KERNEL"
NATIVE = "native"
DIFFERS = "runs here can differ from official grading in the last digits"

# numpy's dispatch targets above x86-64-v3, by the names numpy 1.x/2.0-2.3 (AVX512_*) and 2.4+ (X86_V4) use.
# numpy warns (ImportWarning) about a name it does not dispatch, and ignores it: the filter below hides that.
NUMPY_AVX512 = ("X86_V4", "AVX512F", "AVX512CD", "AVX512_KNL", "AVX512_KNM", "AVX512_SKX", "AVX512_CLX",
                "AVX512_CNL", "AVX512_ICL", "AVX512_SPR")
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
                    "VECLIB_MAXIMUM_THREADS", "NUMEXPR_NUM_THREADS")
PINNED_VARIABLES = ("OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES", *THREAD_VARIABLES)
# OpenBLAS's name for its kernel, by the symbol prefix each numpy wheel generation uses.
_CORENAME_SYMBOLS = ("scipy_openblas_get_corename64_", "openblas_get_corename64_", "openblas_get_corename")
_CONFIG_SYMBOLS = ("scipy_openblas_get_config64_", "openblas_get_config64_", "openblas_get_config")
_missed = False  # numpy had loaded before pin(): what describe() then finds is whatever the shell set


def _machine() -> str:
    """The CPU architecture ("x86_64", "aarch64", "arm64"), without importing platform (~2 ms)."""
    try:
        return os.uname().machine.lower()
    except AttributeError:  # Windows
        import platform

        return platform.machine().lower()


_THREAD_SYMBOLS = ("scipy_openblas_get_num_threads64_", "openblas_get_num_threads64_",
                   "openblas_get_num_threads")


def cpu_flags() -> frozenset[str] | None:
    """The CPU's feature flags (Linux, from /proc/cpuinfo), or None where they cannot be read."""
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as info:
            for line in info:
                if line.startswith("flags"):
                    return frozenset(line.partition(":")[2].split())
    except OSError:
        return None
    return None


def official_kernel(flags: frozenset[str] | None) -> str | None:
    """The kernel this CPU pins: Haswell with AVX2 and FMA, else Nehalem with SSE4.2, else none."""
    if _machine() not in ("x86_64", "amd64") or flags is None:
        return None
    if {"avx2", "fma"} <= flags:
        return OFFICIAL_KERNEL
    if "sse4_2" in flags:
        return FALLBACK_KERNEL
    return None


def plan(environ: dict[str, str] | None = None, flags: frozenset[str] | None = None) -> dict[str, str]:
    """The variables to set before numpy loads (a worker's environment, or this process's own).

    `environ` is read only for the SIMIAM_BLAS_KERNEL override; `flags` defaults to this CPU's."""
    chosen = (os.environ if environ is None else environ).get(OVERRIDE, "").strip()
    if chosen == NATIVE:
        return {OVERRIDE: NATIVE}  # passed on, so a worker's own describe() knows what was chosen
    variables = dict.fromkeys(THREAD_VARIABLES, "1")
    kernel = chosen or official_kernel(cpu_flags() if flags is None else flags)
    if kernel:
        variables["OPENBLAS_CORETYPE"] = kernel
    if _machine() in ("x86_64", "amd64"):
        variables["NPY_DISABLE_CPU_FEATURES"] = " ".join(NUMPY_AVX512)
    if chosen:
        variables[OVERRIDE] = chosen
    return variables


def pin() -> bool:
    """Set this process's numeric environment, if numpy has not loaded yet (True if it could).

    Called when simiam is imported, so `simiam run`, `grade`, the tests and the benchmarks pin it before
    anything imports numpy. A variable already set is replaced: the project, not the shell, chooses."""
    global _missed
    variables = plan()
    if "numpy" in sys.modules:
        # too late to choose; a worker's numpy loaded with these variables already set by its spawner
        _missed = any(os.environ.get(name) != variables.get(name) for name in PINNED_VARIABLES)
        return False
    if os.environ.get(OVERRIDE, "").strip() == NATIVE:
        for name in PINNED_VARIABLES:  # native: what the CPU picks, not what the shell happened to set
            os.environ.pop(name, None)
    os.environ.update(variables)
    warnings.filterwarnings("ignore", message=".*NPY_DISABLE_CPU_FEATURES", category=ImportWarning)
    return True


def _openblas() -> object:
    """The OpenBLAS library numpy loaded (ctypes), or None."""
    import ctypes

    for path in _loaded_libraries():
        if "openblas" in os.path.basename(path).lower():
            try:
                return ctypes.CDLL(path)
            except OSError:
                return None
    return None


def _loaded_libraries() -> list[str]:
    """Paths of the shared libraries mapped into this process (Linux), else numpy's bundled ones."""
    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as maps:
            return list(dict.fromkeys(line.split(None, 5)[5].strip() for line in maps
                                      if len(line.split(None, 5)) == 6 and "/" in line))
    except OSError:
        pass
    numpy = sys.modules.get("numpy")
    found: list[str] = []
    where = getattr(numpy, "__file__", None)
    if isinstance(where, str):
        root = os.path.dirname(where)
        for folder in (os.path.join(root, ".dylibs"), os.path.join(root, "..", "numpy.libs")):
            if os.path.isdir(folder):
                found += [os.path.join(folder, name) for name in sorted(os.listdir(folder))]
    return found


def _call(library: object, symbols: tuple[str, ...], text: bool) -> str | int | None:
    """OpenBLAS's answer from the first of `symbols` the library has (each numpy wheel generation names
    them differently): text (a C string) or an int; None where the library has none of them."""
    import ctypes

    for symbol in symbols:
        function = getattr(library, symbol, None)
        if function is not None:
            function.restype = ctypes.c_char_p if text else ctypes.c_int
            value = function()
            if not text:
                return int(value)
            return value.decode("ascii", "replace").strip()[:200] if value else None
    return None


def _numpy_simd() -> tuple[list[str], bool]:
    """numpy's enabled dispatch targets, and whether any AVX-512 one is among them."""
    import importlib

    for name in ("numpy._core._multiarray_umath", "numpy.core._multiarray_umath"):  # numpy 2.x, 1.x
        try:
            umath = importlib.import_module(name)
            break
        except ImportError:
            continue
    else:
        return [], False
    features = getattr(umath, "__cpu_features__", {})
    enabled = [name for name in getattr(umath, "__cpu_dispatch__", []) if features.get(name)]
    return enabled, any(name in NUMPY_AVX512 or name.startswith("AVX512") for name in enabled)


def describe() -> dict[str, object]:
    """What numeric environment this process really runs (read back after numpy loaded).

    {"machine", "numpy", "blas", "kernel", "threads", "numpy_simd", "official", "note"}:
    `official` is True only where it is the official one (the Haswell kernel, one thread, numpy's loops
    at the AVX2 level); otherwise `note` says what differs and that runs can differ in the last digits."""
    import numpy

    library = _openblas()
    kernel, config, threads = (_call(library, symbols, text) if library is not None else None
                               for symbols, text in ((_CORENAME_SYMBOLS, True), (_CONFIG_SYMBOLS, True),
                                                     (_THREAD_SYMBOLS, False)))
    kernel = kernel if isinstance(kernel, str) else None
    config = config if isinstance(config, str) else None
    enabled, avx512 = _numpy_simd()
    machine = _machine()
    problems = []
    if library is None:
        problems.append("numpy here does not use OpenBLAS (for example Apple's Accelerate), so its "
                        "matrix products cannot be pinned")
    elif kernel is None or kernel.lower() != OFFICIAL_KERNEL.lower():
        wanted = official_kernel(cpu_flags())
        problems.append(f"the BLAS kernel is {kernel or 'unknown'}, not {OFFICIAL_KERNEL}"
                        + (" (this CPU lacks AVX2/FMA)" if wanted != OFFICIAL_KERNEL else ""))
    if threads not in (None, 1):
        problems.append(f"BLAS uses {threads} threads, not 1")
    if avx512:
        problems.append("numpy uses its AVX-512 loops")
    if machine not in ("x86_64", "amd64"):
        problems.append(f"this is a {machine or 'unknown'} CPU, not x86-64")
    if problems and _missed:
        problems.append("numpy was imported before simiam could pin its environment")
    note = "" if not problems else "; ".join(problems) + f": {DIFFERS}"
    return {"machine": machine[:40], "numpy": str(numpy.__version__)[:40],
            "blas": (config or ("OpenBLAS" if library is not None else "not OpenBLAS"))[:200],
            "kernel": (kernel or "")[:40], "threads": threads, "numpy_simd": " ".join(enabled)[:200],
            "official": not problems,
            "note": note[:600]}


_TEXT_FIELDS = {"machine": 40, "numpy": 40, "blas": 200, "kernel": 40, "numpy_simd": 200, "note": 600}


def checked(value: object) -> dict[str, object]:
    """A describe() dict that came from another process, bounded: known keys, plain types, capped text.

    A worker reports its environment before any student code runs, but whatever crosses the pipe is
    treated as hostile all the same; anything malformed reads as "not reported", never as official."""
    if not isinstance(value, dict):
        return {"official": False, "note": f"the worker did not report its numeric environment: {DIFFERS}"}
    out: dict[str, object] = {}
    malformed = False
    for key, cap in _TEXT_FIELDS.items():
        text = value.get(key)
        malformed |= not isinstance(text, str) or len(text) > cap
        out[key] = text[:cap] if isinstance(text, str) else ""
    threads = value.get("threads")
    malformed |= threads is not None and not (type(threads) is int and 0 <= threads < 10_000)
    out["threads"] = threads if type(threads) is int and 0 <= threads < 10_000 else None
    out["official"] = value.get("official") is True and not out["note"] and not malformed
    if not out["official"] and not out["note"]:
        out["note"] = f"the worker's numeric environment is not the official one: {DIFFERS}"
    return out
