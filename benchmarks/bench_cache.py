"""Disk-cache benchmark: cold compute vs warm read, entry sizes, and what the signature costs.

Run: ``python benchmarks/bench_cache.py`` (prints two tables; no assertion: figures go in the notes).

Rows: Duffing's solution to order 3, the disk's solution to order 1 and the disk's reduction, each
computed once (cold), written as a signed entry to a private temporary folder, then read back
(warm: open + HMAC check + header check + unpickle, the whole hit path of ``perturb.cache.cached``).

The second table weighs the alternative to pickle: a code-free tree encoding (JSON of whitelisted
sympy node types).  It is prototyped here on the sympy expressions *only* (a lower bound on its cost:
a real format would also need a schema for each engine class in the tree, listed in the last column),
and compared with unpickling the whole object and with the HMAC-SHA256 check that makes pickle safe.
"""

from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import attrs
import sympy as sp

from perturb import PoincareMethod
from perturb import cache as disk_cache
from perturb.cache_files import write_entry
from problems import get_problem

REPEATS = 5

#: The hit path timed once in a new process (imports done first): sympy's own cache is cold there,
#: as in a fresh ``perturb`` command, and unpickling rebuilds every expression.
_FRESH_READ = """
import sys, time
from pathlib import Path
import problems, sympy
from perturb import cache
path, kind, key = Path(sys.argv[1]), sys.argv[2], sys.argv[3]
secret = cache._secret(path.parent)
start = time.perf_counter()
why, value = cache.decode(path.read_bytes(), kind, key, secret)
print(time.perf_counter() - start if why is None else why)
"""


def _fresh_read(path: Path, kind: str, key: str) -> float:
    out = subprocess.run(
        [sys.executable, "-c", _FRESH_READ, str(path), kind, key],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    return float(out)


#: Node types the prototype tree decoder may build; anything else is refused (never looked up).
_NODES = {
    cls.__name__: cls
    for cls in (sp.Add, sp.Mul, sp.Pow, sp.sin, sp.cos, sp.sqrt, sp.exp, sp.log, sp.Abs)
}
_ATOMS = {"Pi": sp.pi, "E": sp.E, "ImaginaryUnit": sp.I}


def _tree(expr: sp.Basic):
    """``expr`` as nested lists of whitelisted node names and plain data."""
    if isinstance(expr, sp.Symbol):
        return ["Symbol", expr.name, expr.assumptions0]
    if isinstance(expr, sp.Integer):
        return ["Integer", int(expr)]
    if isinstance(expr, sp.Rational):
        return ["Rational", int(expr.p), int(expr.q)]
    if isinstance(expr, sp.Float):
        return ["Float", str(expr), expr._prec]
    name = type(expr).__name__
    if name in _ATOMS:
        return [name]
    if name not in _NODES:
        raise TypeError(f"node {name} is outside the whitelist")
    return [name, *(_tree(arg) for arg in expr.args)]


def _build(tree) -> sp.Basic:
    name, *args = tree
    if name == "Symbol":
        return sp.Symbol(args[0], **args[1])
    if name == "Integer":
        return sp.Integer(args[0])
    if name == "Rational":
        return sp.Rational(args[0], args[1])
    if name == "Float":
        return sp.Float(args[0], precision=args[1])
    if name in _ATOMS:
        return _ATOMS[name]
    return _NODES[name](*(_build(arg) for arg in args))


def _contents(obj, exprs: list, classes: set, seen: set) -> None:
    """Collect the sympy expressions and the engine classes reachable from ``obj``."""
    if id(obj) in seen:
        return
    seen.add(id(obj))
    if isinstance(obj, sp.Basic):
        exprs.append(obj)
        return
    module = type(obj).__module__
    if module.startswith(("perturb", "problems")):
        classes.add(type(obj).__qualname__)
    if attrs.has(type(obj)):
        children = [getattr(obj, f.name) for f in attrs.fields(type(obj))]
    elif isinstance(obj, (tuple, list, set, frozenset)):
        children = list(obj)
    elif isinstance(obj, dict):
        children = [*obj.keys(), *obj.values()]
    else:
        slots = getattr(type(obj), "__slots__", ())
        children = [getattr(obj, s) for s in slots if hasattr(obj, s)]
        children += list(getattr(obj, "__dict__", {}).values())
    for child in children:
        _contents(child, exprs, classes, seen)


def _best(fn, repeats: int = REPEATS) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def _cases():
    duffing = get_problem("duffing").create()
    disk = get_problem("disk").create()
    yield (
        "duffing order 3 solution",
        "solution",
        lambda: PoincareMethod(order=3, cache=False, **duffing.method_options()).solve(
            duffing.system()
        ),
    )
    reduction = []
    yield "disk reduction", "reduction", lambda: reduction.append(disk.reduction()) or reduction[-1]
    yield (
        "disk order 1 solution",
        "solution",
        lambda: PoincareMethod(order=1, cache=False, **disk.method_options()).solve(disk.system()),
    )


def main() -> None:
    folder = Path(tempfile.mkdtemp(prefix="perturb-bench-cache-"))
    os.environ["PERTURB_CACHE_KEY_FILE"] = str(folder.parent / f"{folder.name}.key")
    secret = disk_cache._secret(folder)
    rows, tree_rows = [], []
    for label, kind, compute in _cases():
        start = time.perf_counter()
        value = compute()  # the first call pays for every derivation behind it
        cold = time.perf_counter() - start
        key = disk_cache._key(kind, (label,))
        path = folder / f"{kind}-{key}.pkl"
        blob = disk_cache.encode(kind, key, value, secret)
        write_entry(folder, path, blob)

        def warm(path=path, kind=kind, key=key):
            why, _ = disk_cache.decode(path.read_bytes(), kind, key, secret)
            assert why is None, why

        payload = pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
        body = blob[len(disk_cache._MAGIC) + disk_cache._TAG_SIZE :]
        sign = _best(lambda body=body: disk_cache._sign(secret, body), 50)
        fresh = _fresh_read(path, kind, key)
        rows.append((label, cold, fresh, _best(warm), len(blob), len(payload), sign))

        exprs, classes = [], set()
        _contents(value, exprs, classes, set())
        try:
            text = json.dumps([_tree(e) for e in exprs])
            rebuilt = [_build(t) for t in json.loads(text)]
            assert all(a == b for a, b in zip(exprs, rebuilt, strict=True))
            tree = _best(lambda text=text: [_build(t) for t in json.loads(text)])
            size = f"{len(text):9d}"
        except TypeError as exc:  # a node outside the prototype's whitelist
            tree, size = float("nan"), f"{str(exc).split()[1]:>9s}"
        unpickle = _best(lambda payload=payload: pickle.loads(payload))
        tree_rows.append(
            (label, len(exprs), size, tree, unpickle, sign, ", ".join(sorted(classes)))
        )

    print(
        f"{'entry':26s} {'cold [s]':>9s} {'warm, new process [s]':>21s} {'speed-up':>9s} "
        f"{'warm, again [s]':>15s} {'entry [B]':>10s} {'pickle [B]':>10s} {'HMAC [us]':>10s}"
    )
    for label, cold, fresh, warm_s, size, payload_size, sign in rows:
        print(
            f"{label:26s} {cold:9.3f} {fresh:21.4f} {cold / fresh:9.0f} {warm_s:15.4f} "
            f"{size:10d} {payload_size:10d} {sign * 1e6:10.1f}"
        )
    print()
    print(
        f"{'entry':26s} {'exprs':>5s} {'tree [B]':>9s} {'tree decode [s]':>15s} "
        f"{'unpickle [s]':>12s} {'HMAC [s]':>9s}  engine classes a tree format must describe"
    )
    for label, n, size, tree, unpickle, sign, classes in tree_rows:
        print(f"{label:26s} {n:5d} {size} {tree:15.4f} {unpickle:12.4f} {sign:9.6f}  {classes}")


if __name__ == "__main__":
    main()
