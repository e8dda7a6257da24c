"""A seeded generator of malformed captures, calibrations and configs, and a runner that feeds them
to radaraug's public entry points.

Each case starts from a small valid file made by the project's own writers (a radaraug HDF5
capture, an Infineon recording folder with ``temperature.npy``, a ``CalibratedDR`` JSON) and damages
it in one way: bit flips, truncations, JSON values or HDF5 attributes replaced by hostile values
from :data:`HOSTILE_JSON`, ``.npy`` header edits, HDF5 link tricks and datasets that declare far
more data than the file stores, FIFOs and links to ``/dev/zero`` in place of files.

:func:`run_cases` runs every case in a forked child process (so a hang is a finding, not a stuck
test run, and a runaway allocation hits an address-space limit), against ``open_capture`` +
``read``, the ``info`` command's :func:`radaraug.transforms.summary.summarize_capture`,
``RadarCaptureDataset(...)[0]`` and ``CalibratedDR.load`` (then used). The outcome of a case is
``"ok"``, ``"error:<RadarAugError subclass>"`` (both pass), or a failure: another exception
type, a ``RuntimeWarning``, numpy's ``allow_pickle`` advice in a message, an error message that
does not name the file, a result that breaks an invariant (a negative duration, floats outside
[-1, 1]), a hang or a crash of the process.
"""

from __future__ import annotations

import ast
import json
import os
import random
import resource
import shutil
import signal
import struct
import traceback
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np

# Hostile JSON values, as raw JSON text (some are not expressible with json.dumps: NaN, 401-digit
# integers, 100,000 nested brackets).
HOSTILE_JSON: tuple[str, ...] = (
    "null", "true", "false", "0", "-1", "1", "2", "3", "1.9", "-2.5", "64.5", "1000", "64",
    "1e308", "-1e308", "1e400", "NaN", "Infinity", "-Infinity", "1e-300", "5e-324",
    '""', '"abc"', '"64"', '"500k"', '"1"', '"tdm"', '"off"',
    "[]", "[0]", "[-2]", "[99]", "[1.9]", '["1"]', "[1]", "[1, 2]", "[true]", "[null]", "[[1]]",
    "{}", '{"a": 1}', '{"name": 1}', '[{"x": 1}]', '[{"name": null}]',
    "18446744073709551616", "9223372036854775807", "-9223372036854775809",
    "1" * 401, "9" * 5000, "[" * 100_000 + "]" * 100_000, '"' + "x" * 100_000 + '"',
)

NPY_SHAPES: tuple[str, ...] = (
    "(18446744073709551616, 3, 4, 32)", "(-1, 3, 4, 32)", "(9223372036854775807, 3, 4, 32)",
    "(0, 4611686018427387904, 4611686018427387904, 128)", "(True, 3, 4, 32)", "(5.0, 3, 4, 32)",
    "(5, 3, 4)", "()", "(1099511627776,)", "(5, 3, 4, 32, 1)", "'abc'", "(None, 3, 4, 32)",
    "(6, 3, 4, 32)", "(4, 3, 4, 32)", "[5, 3, 4, 32]",
)
NPY_DESCRS: tuple[str, ...] = (
    "'|O'", "'<f8'", "'<u4'", "'<i8'", "'|b1'", "'(2,)<u2'", "'|V4'", "'abc'", "'>u2'",
    "[('a', '<u2')]", "'<U3'", "0",
)


@dataclass
class Case:
    """One malformed input: ``build(case_dir) -> path`` and which entry points it goes to."""

    name: str
    kind: str  # "capture" or "cdr"
    build: Callable[[Path], Path]


# ----------------------------------------------------------------------------- base files
def _json_with(base: dict, key_path: tuple[str, ...], raw: str | None) -> str:
    """``base`` as JSON with ``key_path`` set to the raw JSON text ``raw`` (None: key removed)."""
    data = json.loads(json.dumps(base))
    node = data
    for k in key_path[:-1]:
        node = node[k]
    if raw is None:
        node.pop(key_path[-1], None)
        return json.dumps(data)
    node[key_path[-1]] = "@@HOSTILE@@"
    return json.dumps(data).replace('"@@HOSTILE@@"', raw)


def make_bases(folder: Path) -> dict[str, Path]:
    """Write the valid base files every case mutates: an HDF5 capture, an Infineon recording
    (with temperature) and a CalibratedDR JSON, all from the tiny config of ``tests/io/data.py``."""
    import radaraug_tests_io_data as io_data

    from radaraug.io import write_capture, write_infineon_recording
    from radaraug.transforms import CalibratedDR, RangeDoppler, ToDecibels

    cfg = io_data.tiny_config()
    counts = io_data.tone_counts(cfg, 6, seed=1)
    folder.mkdir(parents=True, exist_ok=True)
    h5 = write_capture(
        folder / "base.h5", counts, cfg, timestamps=1.7e9 + 0.01 * np.arange(6),
        labels={"count": np.array([0, 0, 1, 1, 2, 2]), "room": 3},
    )
    rec = write_infineon_recording(folder / "rec", counts[:5], cfg, timestamps=1.7e9 + 0.01 * np.arange(5))
    np.save(rec / "RadarIfxAvian_00" / "temperature.npy", np.full((5, 1), 31.5, np.float32))
    chain = [RangeDoppler().chain_spec(), ToDecibels().chain_spec()]
    cdr = CalibratedDR(-95.0, 2.0, chain=chain, config=cfg, map_shape=(3, 16, 4), source="fuzz base")
    cdr_path = folder / "cdr.json"
    cdr.save(cdr_path)
    return {"h5": h5, "rec": rec, "cdr": cdr_path}


# ----------------------------------------------------------------------------- mutations
def _copy(src: Path, dst_dir: Path, name: str | None = None) -> Path:
    dst = dst_dir / (name or src.name)
    if src.is_dir():
        shutil.copytree(src, dst)
    else:
        shutil.copyfile(src, dst)
    return dst


def _flip_bits(path: Path, rng: random.Random, count: int, lo: int, hi: int) -> None:
    data = bytearray(path.read_bytes())
    hi = min(hi, len(data))
    for _ in range(count):
        i = rng.randrange(lo, hi)
        data[i] ^= 1 << rng.randrange(8)
    path.write_bytes(bytes(data))


def _truncate(path: Path, keep: int) -> None:
    data = path.read_bytes()
    path.write_bytes(data[: max(0, keep)])


def _npy_with_header(path: Path, *, shape: str | None = None, descr: str | None = None,
                     fortran: str | None = None, nul: bool = False, version: bytes | None = None,
                     header_len: int | None = None) -> None:
    """Rewrite a version 1.0 .npy header with edited fields, keeping the data bytes."""
    raw = path.read_bytes()
    hlen = struct.unpack("<H", raw[8:10])[0]
    header = raw[10 : 10 + hlen].decode("latin1")
    body = raw[10 + hlen :]
    d = ast.literal_eval(header)  # the header of a file np.save just wrote
    descr = descr if descr is not None else repr(d["descr"])
    fortran = fortran if fortran is not None else repr(d["fortran_order"])
    shape = shape if shape is not None else repr(d["shape"])
    text = f"{{'descr': {descr}, 'fortran_order': {fortran}, 'shape': {shape}, }}"
    pad = 64 - (10 + len(text) + 1) % 64
    text = text + (" " * (pad - 1) + "\x00" if nul and pad > 0 else " " * pad) + "\n"
    magic = b"\x93NUMPY" + (version or b"\x01\x00")
    length = header_len if header_len is not None else len(text)
    path.write_bytes(magic + struct.pack("<H", length) + text.encode("latin1") + body)


def _fifo(path: Path) -> None:
    if path.exists():
        path.unlink()
    os.mkfifo(path)


def _zero_link(path: Path) -> None:
    if path.exists():
        path.unlink()
    os.symlink("/dev/zero", path)


def _h5_edit(path: Path, edit: Callable[[h5py.File], None]) -> None:
    with h5py.File(path, "r+") as f:
        edit(f)


def _fix_superblock_checksum(data: bytearray) -> bool:
    """Recompute a v2/v3 superblock checksum after an edit (needs radaraug's lookup3)."""
    try:
        from radaraug.io.hdf5_format import lookup3
    except ImportError:  # a radaraug without it: the edit stays unchecksummed
        return False
    so = data[9]
    end = 12 + 4 * so
    data[end : end + 4] = struct.pack("<I", lookup3(bytes(data[:end])))
    return True


def generate_cases(bases: dict[str, Path], seed: int, scale: int = 1) -> list[Case]:
    """The seeded list of malformed inputs (``scale`` multiplies the random mutations and takes
    every (key, hostile value) pair instead of a sample)."""
    rng = random.Random(seed)
    cases: list[Case] = []
    h5, rec, cdr = bases["h5"], bases["rec"], bases["cdr"]
    dev = "RadarIfxAvian_00"

    def add(name: str, kind: str, build: Callable[[Path], Path]) -> None:
        cases.append(Case(name, kind, build))

    def sample(pairs: list, k: int) -> list:
        return pairs if scale > 1 or k >= len(pairs) else rng.sample(pairs, k)

    # --- Infineon config.json values
    cfg_json = json.loads((rec / dev / "config.json").read_text())
    shape_keys = list(cfg_json["device_config"]["fmcw_single_shape"]) + ["mimo_mode", "unknown_key"]
    pairs = [(k, v) for k in shape_keys for v in HOSTILE_JSON] + [(k, None) for k in shape_keys]
    for key, raw in sample(pairs, 110):
        def build(d: Path, key=key, raw=raw) -> Path:
            r = _copy(rec, d)
            (r / dev / "config.json").write_text(
                _json_with(cfg_json, ("device_config", "fmcw_single_shape", key), raw))
            return r
        add(f"infineon-config {key}={(raw or 'DELETED')[:20]}", "capture", build)
    for raw in sample(list(HOSTILE_JSON), 12):
        def build(d: Path, raw=raw) -> Path:
            r = _copy(rec, d)
            (r / dev / "config.json").write_text(raw)
            return r
        add(f"infineon-config whole={raw[:20]}", "capture", build)

    # --- HDF5 radar_config attribute values
    with h5py.File(h5, "r") as f:
        h5_cfg = json.loads(f.attrs["radar_config"])
    pairs = [(k, v) for k in list(h5_cfg) + ["unknown_key"] for v in HOSTILE_JSON]
    for key, raw in sample(pairs, 60):
        def build(d: Path, key=key, raw=raw) -> Path:
            p = _copy(h5, d)
            _h5_edit(p, lambda f: f.attrs.__setitem__("radar_config", _json_with(h5_cfg, (key,), raw)))
            return p
        add(f"h5-config {key}={raw[:20]}", "capture", build)

    # --- HDF5 label attributes
    for raw in sample(list(HOSTILE_JSON), 20):
        def build(d: Path, raw=raw) -> Path:
            p = _copy(h5, d)
            _h5_edit(p, lambda f: f.attrs.__setitem__("labels", '{"who": ' + raw + "}"))
            return p
        add(f"h5-labels who={raw[:20]}", "capture", build)
    for raw in sample(list(HOSTILE_JSON), 8):
        def build(d: Path, raw=raw) -> Path:
            p = _copy(h5, d)
            _h5_edit(p, lambda f: f.attrs.__setitem__("labels", raw))
            return p
        add(f"h5-labels whole={raw[:20]}", "capture", build)
    label_attrs = {
        "empty": h5py.Empty("f8"), "array6": np.arange(6), "array2x3": np.ones((2, 3)),
        "bytes": np.bytes_(b"\xff\xfe"), "strings": np.array([b"a", b"b"]), "nan": np.nan,
        "bool": np.bool_(True), "big": np.uint64(2**64 - 1),
    }
    for lname, value in label_attrs.items():
        def build(d: Path, value=value) -> Path:
            p = _copy(h5, d)
            _h5_edit(p, lambda f: f.attrs.__setitem__("label_x", value))
            return p
        add(f"h5-label_x {lname}", "capture", build)

    # --- HDF5 structure: links, declared sizes, unwritten chunks, odd datasets
    def frames_resized(n: int):
        return lambda f: f["frames"].resize(n, axis=0)

    def relink(name: str, link):
        def edit(f: h5py.File) -> None:
            del f[name]
            f[name] = link
        return edit

    def ext_frames(d: Path) -> Path:
        other = _copy(h5, d, "other.h5")
        p = _copy(h5, d)
        _h5_edit(p, relink("frames", h5py.ExternalLink(str(other), "/frames")))
        return p

    def middle_gap(f: h5py.File) -> None:
        ds = f["frames"]
        ds.resize(12, axis=0)
        ds[11] = ds[0]
        f["timestamps"].resize(12, axis=0)
        f["timestamps"][6:] = 1.7e9 + 0.01 * np.arange(6, 12)
        f["labels/count"].resize(12, axis=0)

    def contiguous_unwritten(f: h5py.File) -> None:
        shape = f["frames"].shape
        del f["frames"]
        f.create_dataset("frames", shape=shape, dtype=np.uint16)

    def huge_frames_config(f: h5py.File) -> None:
        c = dict(h5_cfg, num_samples_per_chirp=2**22, sample_rate_Hz=1e12)
        f.attrs["radar_config"] = json.dumps(c)
        del f["frames"]
        f.create_dataset("frames", shape=(6, 3, 4, 2**22), maxshape=(None, 3, 4, 2**22),
                         chunks=(1, 3, 4, 2**16), dtype=np.uint16)

    structural = {
        "frames-self-softlink": relink("frames", h5py.SoftLink("/frames")),
        "timestamps-dangling": relink("timestamps", h5py.SoftLink("/nowhere")),
        "labels-dangling": relink("labels/count", h5py.SoftLink("/nowhere")),
        "frames-group": lambda f: (f.__delitem__("frames"), f.create_group("frames")),
        "frames-2pow40": frames_resized(2**40),
        "frames-trailing-unwritten": frames_resized(9),
        "frames-middle-gap": middle_gap,
        "frames-contiguous-unwritten": contiguous_unwritten,
        "frames-2pow22-samples": huge_frames_config,
        "timestamps-2pow31": lambda f: f["timestamps"].resize(2**31, axis=0),
        "timestamps-2pow27": lambda f: f["timestamps"].resize(2**27, axis=0),
        "labels-2pow27": lambda f: f["labels/count"].resize(2**27, axis=0),
        "labels-2pow31": lambda f: f["labels/count"].resize(2**31, axis=0),
        "timestamps-decreasing": lambda f: f["timestamps"].__setitem__(slice(None), 1.7e9 - np.arange(6.0)),
        "timestamps-strings": lambda f: (f.__delitem__("timestamps"), f.create_dataset("timestamps", data=[b"a"] * 6)),
        "labels-strings": lambda f: (f.__delitem__("labels/count"), f.create_dataset("labels/count", data=[b"a"] * 6)),
        "labels-2d": lambda f: (f.__delitem__("labels/count"), f.create_dataset("labels/count", data=np.ones((6, 2)))),
        "labels-compound": lambda f: (f.__delitem__("labels/count"), f.create_dataset(
            "labels/count", data=np.zeros(6, dtype=[("a", "<i4"), ("b", "<f8")]))),
        "labels-not-group": lambda f: (f.__delitem__("labels"), f.create_dataset("labels", data=np.arange(6))),
        "format-version-9": lambda f: f.attrs.__setitem__("format_version", "9.0"),
        "format-empty": lambda f: f.attrs.__setitem__("format", h5py.Empty("f8")),
        "radar-config-empty": lambda f: f.attrs.__setitem__("radar_config", h5py.Empty("f8")),
        "radar-config-array": lambda f: f.attrs.__setitem__("radar_config", np.arange(3)),
        "frames-above-full-scale": lambda f: f["frames"].__setitem__(0, 4096),
    }
    for sname, edit in structural.items():
        def build(d: Path, edit=edit) -> Path:
            p = _copy(h5, d)
            _h5_edit(p, edit)
            return p
        add(f"h5-struct {sname}", "capture", build)
    add("h5-struct frames-external-link", "capture", ext_frames)

    # --- HDF5 bytes: flips in the metadata, truncations, superblock fields
    size = h5.stat().st_size
    for i in range(25 * scale):
        flips = 1 + i % 4
        def build(d: Path, i=i, flips=flips) -> Path:
            p = _copy(h5, d)
            _flip_bits(p, random.Random(seed * 1000 + i), flips, 0, 4096)
            return p
        add(f"h5-flip4k {i} x{flips}", "capture", build)
    for i in range(8 * scale):
        def build(d: Path, i=i) -> Path:
            p = _copy(h5, d)
            _flip_bits(p, random.Random(seed * 2000 + i), 8, 0, size)
            return p
        add(f"h5-flipall {i}", "capture", build)
    for keep in [12, 48, 100, 2048, size // 2, size - 12, size - 1] + [rng.randrange(size) for _ in range(4 * scale)]:
        def build(d: Path, keep=keep) -> Path:
            p = _copy(h5, d)
            _truncate(p, keep)
            return p
        add(f"h5-truncate {keep}", "capture", build)
    for fix in (False, True):
        for delta in (-5000, -1, 5000):
            def build(d: Path, delta=delta, fix=fix) -> Path:
                p = _copy(h5, d)
                data = bytearray(p.read_bytes())
                so = data[9]
                at = 12 + 2 * so
                eof = int.from_bytes(data[at : at + so], "little") + delta
                data[at : at + so] = eof.to_bytes(so, "little")
                if fix:
                    _fix_superblock_checksum(data)
                p.write_bytes(bytes(data))
                return p
            add(f"h5-superblock eof{delta:+d} {'fixed' if fix else 'raw'}", "capture", build)
    for flags in (1, 5, 255):
        def build(d: Path, flags=flags) -> Path:
            p = _copy(h5, d)
            data = bytearray(p.read_bytes())
            data[11] = flags
            _fix_superblock_checksum(data)
            p.write_bytes(bytes(data))
            return p
        add(f"h5-superblock flags={flags}", "capture", build)

    # --- radar.npy and temperature.npy headers
    for target in ("radar.npy", "temperature.npy"):
        edits: list[tuple[str, dict]] = [(f"shape={s[:24]}", {"shape": s}) for s in NPY_SHAPES]
        edits += [(f"descr={s}", {"descr": s}) for s in NPY_DESCRS]
        edits += [("fortran=True", {"fortran": "True"}), ("fortran=1", {"fortran": "'x'"}),
                  ("nul-padding", {"nul": True}), ("version=3.0", {"version": b"\x03\x00"}),
                  ("version=9.9", {"version": b"\x09\x09"}), ("header_len=65535", {"header_len": 65535}),
                  ("header_len=0", {"header_len": 0})]
        if target == "temperature.npy":
            edits = [e for e in edits if e[0].startswith(("shape=(1099", "shape=(-1", "shape=(True", "descr='|O",
                                                          "nul", "version=9", "header_len=6", "shape=(184"))]
        for ename, kw in edits:
            def build(d: Path, target=target, kw=kw) -> Path:
                r = _copy(rec, d)
                path = r / dev / target
                if target == "temperature.npy" and "shape" in kw and kw["shape"].startswith("(1099"):
                    np.save(path, np.zeros(36, np.float32))  # the 144-byte file
                    kw = {**kw, "shape": "(1099511627776,)"}
                _npy_with_header(path, **kw)
                return r
            add(f"npy {target} {ename}", "capture", build)
    npy_size = (rec / dev / "radar.npy").stat().st_size
    for keep in (0, 6, 9, 60, 128, npy_size - 1):
        def build(d: Path, keep=keep) -> Path:
            r = _copy(rec, d)
            _truncate(r / dev / "radar.npy", keep)
            return r
        add(f"npy radar.npy truncate {keep}", "capture", build)
    def appended(d: Path) -> Path:
        r = _copy(rec, d)
        with open(r / dev / "radar.npy", "ab") as fh:
            fh.write(b"\0" * 100)
        return r
    add("npy radar.npy trailing-bytes", "capture", appended)
    for i in range(6 * scale):
        def build(d: Path, i=i) -> Path:
            r = _copy(rec, d)
            _flip_bits(r / dev / "radar.npy", random.Random(seed * 3000 + i), 2, 0, 128)
            return r
        add(f"npy radar.npy header-flip {i}", "capture", build)

    # --- timestamps CSV, format.version, meta.json
    csv_texts = {
        "text": "abc\n" * 5, "nan": "nan\n" * 5, "huge-digits": ("9" * 5000 + "\n") * 5, "1e400": "1e400\n" * 5,
        "decreasing": "".join(f"{1.7e9 - i}\n" for i in range(5)), "binary": "\xff\xfe\x00\n",
        "long-line": "1" * 1_000_000, "many-lines": "1.7e9\n" * 200_000, "empty": "",
    }
    for cname, text in csv_texts.items():
        def build(d: Path, text=text) -> Path:
            r = _copy(rec, d)
            (r / dev / "radar_timestamp.csv").write_bytes(text.encode("latin1"))
            return r
        add(f"csv {cname}", "capture", build)
    for vname, text in {"9.0.0": "9.0.0", "binary": "\xff\x00", "long": "1" * 100_000}.items():
        def build(d: Path, text=text) -> Path:
            r = _copy(rec, d)
            (r / dev / "format.version").write_bytes(text.encode("latin1"))
            return r
        add(f"format.version {vname}", "capture", build)
    for where in ("meta.json", f"{dev}/meta.json"):
        for raw in ("[" * 100_000 + "]" * 100_000, "9" * 5000, "[1]", "\xff", "{"):
            def build(d: Path, where=where, raw=raw) -> Path:
                r = _copy(rec, d)
                (r / where).write_bytes(raw.encode("latin1"))
                return r
            add(f"meta {where} {raw[:12]}", "capture", build)
    for i in range(4 * scale):
        def build(d: Path, i=i) -> Path:
            r = _copy(rec, d)
            _flip_bits(r / dev / "config.json", random.Random(seed * 4000 + i), 3, 0, 10**9)
            return r
        add(f"infineon-config flip {i}", "capture", build)

    # --- FIFOs and /dev/zero in place of files
    for special, fn in (("fifo", _fifo), ("devzero", _zero_link)):
        for target in ("radar.npy", "config.json", "radar_timestamp.csv", "format.version", "meta.json",
                       "temperature.npy"):
            def build(d: Path, target=target, fn=fn) -> Path:
                r = _copy(rec, d)
                fn(r / dev / target)
                return r
            add(f"{special} {target}", "capture", build)
        def build_top(d: Path, fn=fn) -> Path:
            r = _copy(rec, d)
            fn(r / "meta.json")
            return r
        add(f"{special} recording meta.json", "capture", build_top)
        for cname in ("capture.h5", "capture"):
            def build(d: Path, cname=cname, fn=fn) -> Path:
                p = d / cname
                fn(p)
                return p
            add(f"{special} {cname}", "capture", build)
        def build_cdr(d: Path, fn=fn) -> Path:
            p = d / "cdr.json"
            fn(p)
            return p
        add(f"{special} cdr.json", "cdr", build_cdr)

    # --- cdr.json
    cdr_json = json.loads(cdr.read_text())
    pairs = [(k, v) for k in cdr_json for v in HOSTILE_JSON] + [(k, None) for k in cdr_json]
    for key, raw in sample(pairs, 55):
        def build(d: Path, key=key, raw=raw) -> Path:
            p = d / "cdr.json"
            p.write_text(_json_with(cdr_json, (key,), raw))
            return p
        add(f"cdr {key}={(raw or 'DELETED')[:20]}", "cdr", build)
    for raw in ('[{"x": 1}]', '[{"name": 5}]', "[1]", '[{"name": "RangeDoppler", "range_window": [1]}]'):
        def build(d: Path, raw=raw) -> Path:
            p = d / "cdr.json"
            p.write_text(_json_with(cdr_json, ("chain",), raw))
            return p
        add(f"cdr chain={raw[:24]}", "cdr", build)
    for raw in ("[" * 100_000 + "]" * 100_000, "9" * 5000, "", "\xff"):
        def build(d: Path, raw=raw) -> Path:
            p = d / "cdr.json"
            p.write_bytes(raw.encode("latin1"))
            return p
        add(f"cdr whole={raw[:12]}", "cdr", build)
    for i in range(5 * scale):
        def build(d: Path, i=i) -> Path:
            p = _copy(cdr, d)
            _flip_bits(p, random.Random(seed * 5000 + i), 2, 0, 10**9)
            return p
        add(f"cdr flip {i}", "cdr", build)
    return cases


# ----------------------------------------------------------------------------- running
def _names_file(message: str, target: Path, case_dir: Path) -> bool:
    return case_dir.name in message or target.name in message


def run_one(case: Case, case_dir: Path) -> str:
    """Build one case and feed it to the entry points; the outcome string (see the module doc)."""
    import torch

    from radaraug.errors import RadarAugError
    from radaraug.io import RadarCaptureDataset, open_capture
    from radaraug.transforms import CalibratedDR, RadarCompose, RangeDoppler, ToDecibels
    from radaraug.transforms.summary import summarize_capture

    case_dir.mkdir(parents=True)
    target = case.build(case_dir)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            if case.kind == "capture":
                with open_capture(target) as cap:
                    x = cap.read(0, min(cap.num_frames, 3))
                    if not (x.abs() <= 1).all():
                        return "wrong: floats outside [-1, 1]"
                    if not cap.duration_s > 0:
                        return f"wrong: duration {cap.duration_s}"
                    info = summarize_capture(cap, max_frames=8)
                    json.dumps(info)
                ds = RadarCaptureDataset([target])
                ds[0]
            else:
                cdr = CalibratedDR.load(target)
                RadarCompose([RangeDoppler(), ToDecibels(), cdr])
                shape = cdr.map_shape or (3, 16, 4)
                cdr(torch.full((2, *shape), -120.0))
            outcome = "ok"
        except RadarAugError as e:
            msg = str(e)
            if "allow_pickle" in msg:
                return f"leak: numpy advice in {type(e).__name__}"
            if not _names_file(msg, target, case_dir):
                return f"noname:{type(e).__name__}: {msg[:160]}"
            outcome = f"error:{type(e).__name__}"
        except Exception as e:  # noqa: BLE001 - any other type is the finding
            tb = traceback.extract_tb(e.__traceback__)[-1]
            return f"bad:{type(e).__name__}: {str(e)[:120]} @ {Path(tb.filename).name}:{tb.lineno}"
    for w in caught:
        if issubclass(w.category, RuntimeWarning):
            return f"warn:{w.category.__name__}: {str(w.message)[:120]}"
        if "allow_pickle" in str(w.message):
            return "leak: numpy advice in a warning"
    return outcome


def _child(cases: list[Case], start: int, root: Path, conn, memory_bytes: int) -> None:
    import torch

    # The parent's OpenMP thread pool does not survive fork(): a parallel torch op in the child
    # would wait for threads that do not exist. Single-threaded ops never enter the pool.
    torch.set_num_threads(1)
    # Bound the address space so an unbounded allocation becomes a MemoryError (a finding),
    # not a machine that swaps.
    vm = 0
    with open("/proc/self/status") as fh:
        for line in fh:
            if line.startswith("VmSize:"):
                vm = int(line.split()[1]) * 1024
    resource.setrlimit(resource.RLIMIT_AS, (vm + memory_bytes, resource.RLIM_INFINITY))
    for i in range(start, len(cases)):
        conn.send(("start", i))
        try:
            outcome = run_one(cases[i], root / f"c{i:05d}")
        except MemoryError:
            outcome = "bad:MemoryError"
        except BaseException as e:  # noqa: BLE001 - a failure of the builder is reported too
            outcome = f"bad:{type(e).__name__} (builder or runner): {str(e)[:100]}"
        conn.send(("done", i, outcome))
    conn.send(("end",))


def run_cases(cases: list[Case], root: Path, *, timeout_s: float = 10.0,
              memory_bytes: int = 3 << 30) -> list[str]:
    """Run every case in forked children; a case that exceeds ``timeout_s`` is ``"hang"`` (its
    child is killed and a new one goes on with the next case)."""
    import multiprocessing as mp

    ctx = mp.get_context("fork")
    outcomes: list[str | None] = [None] * len(cases)
    start = 0
    while start < len(cases):
        parent, child = ctx.Pipe()
        proc = ctx.Process(target=_child, args=(cases, start, root, child, memory_bytes), daemon=True)
        proc.start()
        child.close()
        current = start
        try:
            while True:
                if not parent.poll(timeout_s):
                    outcomes[current] = "hang"
                    break
                msg = parent.recv()
                if msg[0] == "start":
                    current = msg[1]
                elif msg[0] == "done":
                    outcomes[msg[1]] = msg[2]
                    current = msg[1] + 1
                else:
                    current = len(cases)
                    break
        except EOFError:
            outcomes[current] = f"crash: exit code {proc.exitcode}"
        if proc.is_alive():
            os.kill(proc.pid, signal.SIGKILL)
        proc.join()
        if current < len(cases) and outcomes[current] is None:
            outcomes[current] = f"crash: exit code {proc.exitcode}"
        start = current + 1
    return [o or "missing" for o in outcomes]


def is_failure(outcome: str) -> bool:
    """True for every outcome except success and a RadarAugError."""
    return not (outcome == "ok" or outcome.startswith("error:"))
