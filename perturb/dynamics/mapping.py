"""A basin map's layout: its arrays, their meanings, kept in memory or in a resumable store.

The map of a basin study (:mod:`perturb.dynamics.basins`) has one value per initial state of
``code`` (where the motion goes: an attractor's index, or an outcome's negative code), ``periods``
(until classified), ``final`` and ``initial`` (states, along ``component``), and ``session``
(the run that wrote it: the store's commit mark). Small maps are kept in memory
(:class:`MemoryMap`); with ``output`` they are a Zarr store
(:class:`perturb.sweep.store.MapStore`, the sweep store's rules), whose attributes hold the
catalogue and the orbits found so far, so that a resumed run classifies the same way.
"""

from __future__ import annotations

import json
import math

import numpy as np

from perturb.dynamics.classify import Outcome, outcome_meanings

__all__ = ["MemoryMap", "assemble", "code_attributes", "meanings", "open_sink", "stored_catalogue"]


def stored_catalogue(output):
    """The catalogue and found orbits kept in the store at ``output`` (None: no such store)."""
    from pathlib import Path

    from perturb.sweep.store import open_dataset

    if output is None or not Path(output).is_dir():
        return None
    try:
        attrs = open_dataset(output).attrs
    except Exception:  # noqa: BLE001 - not a readable store: MapStore refuses it below
        return None
    if "catalogue" not in attrs:
        return None
    from perturb.dynamics.attractors import decode_state

    found = [decode_state(s) for s in json.loads(attrs.get("found", "[]"))]
    return attrs["catalogue"], found


class MemoryMap:
    """The arrays of a study kept in memory (no store), written chunk by chunk as a store is."""

    def __init__(self, job):
        shape, m = job.shape, job.motion.m
        self.chunking = job.chunking
        self.arrays = {
            "code": np.full(shape, Outcome.NOT_COMPUTED.code, dtype=np.int16),
            "periods": np.zeros(shape, dtype=np.int32),
            "final": np.full((*shape, m), np.nan),
            "initial": np.full((*shape, m), np.nan),
            "session": np.zeros(shape, dtype=np.int32),
        }
        self.extra: dict = {}

    def pending(self) -> list[int]:
        return list(self.chunking)

    def begin_session(self) -> int:
        return 1

    def write(self, number: int, result: dict) -> None:
        region = self.chunking.region(number)
        block = tuple(s.stop - s.start for s in region)
        for name, array in self.arrays.items():
            values = np.asarray(result[name])
            array[region] = values.reshape(block + values.shape[1:])

    def update(self, attrs: dict) -> None:
        self.extra.update(attrs)

    def close(self) -> None:
        return None


def _layout(job) -> dict:
    components = ("component", np.array(job.motion.names, dtype=str))
    return {
        "code": ("int16", Outcome.NOT_COMPUTED.code, {"long_name": "where the motion goes"}, None),
        "periods": ("int32", 0, {"long_name": "drive periods until classified"}, None),
        "final": (
            "float64",
            math.nan,
            {"long_name": "the last stroboscopic return computed"},
            components,
        ),  # fmt: skip
        "initial": ("float64", math.nan, {"long_name": "the initial state"}, components),
    }


def _attributes(job, chart, encode) -> dict:
    return {
        "kind": "basins",
        "problem": chart.problem,
        "parameters": json.dumps({k: float(v) for k, v in chart.values.items()}),
        "order": chart.order,
        "phase": chart.phase,
        "omega": chart.omega,
        "periods_cap": job.cap,
        "backend": job.backend,
        "mode": "samples" if job.sampled else "grid",
        "box": json.dumps([list(b) for b in job.box]),
        "base": json.dumps(dict(zip(job.motion.names, job.base.tolist(), strict=True))),
        "seed": job.seed,
        "catalogue": encode(chart),
        "found": "[]",
    }


def open_sink(job, output, resume: bool, chart):
    """Where the study's chunks are written: a :class:`perturb.dynamics.mapping.MemoryMap`, or the store ``output``
    created (or opened to resume) for this very study."""
    from perturb.dynamics.attractors import encode

    if output is None:
        return MemoryMap(job)
    import perturb
    from perturb.sweep.mapstore import MapStore

    return MapStore.prepare_map(
        output, fingerprint=job.fingerprint(perturb.__version__), label=chart.problem,
        axes=list(job.axes), arrays=_layout(job), chunk=job.chunk,
        attrs=_attributes(job, chart, encode), resume=resume,
    )  # fmt: skip


def meanings(chart) -> tuple[dict, dict]:
    names = {k: s.name for k, s in enumerate(chart.attractors)}
    words = {k: f"{s.name}: {s.kind.value}" for k, s in enumerate(chart.attractors)}
    for code, text in outcome_meanings().items():
        names[code] = text.split(":")[0]
        words[code] = text
    return names, words


def code_attributes(chart) -> dict:
    names, words = meanings(chart)
    codes = sorted(names)
    return {
        "long_name": "where the motion goes",
        "meanings": json.dumps({str(k): words[k] for k in codes}),
        "names": json.dumps({str(k): names[k] for k in codes}),
        "flag_values": codes,
        "flag_meanings": " ".join(names[k].replace(" ", "_") for k in codes),
    }


def assemble(job, sink, chart):
    """The map as an ``xarray.Dataset`` (read lazily from a store), its codes' meanings and the
    catalogue (with the orbits found) in its attributes."""
    from perturb.dynamics.attractors import encode
    from perturb.sweep.memory import dataset_of

    if isinstance(sink, MemoryMap):
        dims = tuple(n for n, _ in job.axes)
        coords = {n: np.asarray(v) for n, v in job.axes}
        coords["component"] = np.array(job.motion.names, dtype=str)
        layout = _layout(job)
        data = {
            name: ((*dims, "component") if layout[name][3] is not None else dims,
                   sink.arrays[name], dict(layout[name][2]))
            for name in ("code", "periods", "final", "initial")
        }  # fmt: skip
        attrs = {**_attributes(job, job.catalogue, encode), **sink.extra}
        dataset = dataset_of(coords, data, attrs)
    else:
        from perturb.sweep.store import open_dataset

        dataset = open_dataset(sink.path)
    dataset["code"].attrs.update(code_attributes(chart))
    dataset.attrs["catalogue"] = encode(chart)
    return dataset
