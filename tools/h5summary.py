#!/usr/bin/python3
"""Readable summary of a narrows HDF5 file (observables.h5, checkpoint-*.h5, ...).

Usage: h5summary.py FILE [FILE ...]

Prints the tree of groups and datasets with shapes, dtypes and attributes; for each
/observables/<name> time series also the number of samples and the last step.
Exit code 2 (one line on stderr) if a file is missing or not HDF5.
"""

import os
import sys

import numpy as np

import narrows_h5

MAX_VALUE_CHARS = 70


def short(text):
    text = " ".join(str(text).split())
    return text if len(text) <= MAX_VALUE_CHARS else text[: MAX_VALUE_CHARS - 3] + "..."


def format_value(value):
    if isinstance(value, bytes):
        value = value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "OS":
            value = [v.decode("utf-8", errors="replace") if isinstance(v, bytes) else v
                     for v in value.ravel()]
        else:
            return short(np.array2string(value, separator=", ", threshold=8))
    elif isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, str):
        return repr(short(value))
    return short(value)


def format_dtype(dset):
    string_info = narrows_h5.string_info(dset.dtype)
    if string_info is not None:
        return "string" if string_info.length is None else f"string[{string_info.length}]"
    return str(dset.dtype)


def format_shape(shape):
    if shape is None:
        return "null"
    if shape == ():
        return "scalar"
    return "[" + "][".join(str(n) for n in shape) + "]"


def describe_dataset(dset):
    text = f"{format_shape(dset.shape)} {format_dtype(dset)}"
    if dset.shape == ():
        value = dset[()]
        if narrows_h5.string_info(dset.dtype) is not None:
            if isinstance(value, bytes):
                value = value.decode("utf-8", errors="replace")
            lines = value.count("\n") + (0 if value.endswith("\n") or not value else 1)
            text += f", {len(value)} chars, {lines} lines"
        else:
            text += f" = {format_value(value)}"
    elif dset.shape is not None and dset.chunks is None and dset.size <= 6 and dset.dtype.kind in "biuf":
        text += f" = {format_value(dset[()])}"
    if dset.chunks is not None and dset.maxshape and dset.maxshape[0] is None:
        text += ", extendible"
    return text


def time_series_note(group):
    """'N samples, last step S' for an H5MD time series group {step, time, value}."""
    if not narrows_h5.is_dataset(group.get("value")):
        return None
    value = group["value"]
    samples = value.shape[0] if value.shape else 1
    step = group.get("step")
    if not narrows_h5.is_dataset(step):
        return f"{samples} samples"
    if step.shape == ():
        last = step[()]
    elif step.shape[0] > 0:
        last = step[-1]
    else:
        return "0 samples"
    return f"{samples} samples, last step {int(last)}"


def print_attributes(obj, indent):
    for name, value in obj.attrs.items():
        print(f"{indent}  @{name} = {format_value(value)}")


def print_tree(group, depth):
    indent = "  " * depth
    for name in group:
        target = narrows_h5.link_target(group, name)
        if target is not None:
            print(f"{indent}{name} -> {target}")
            continue
        obj = group[name]
        if narrows_h5.is_group(obj):
            note = None
            if obj.name.startswith("/observables/") and obj.name.count("/") == 2:
                note = time_series_note(obj)
            print(f"{indent}{name}/" + (f"  ({note})" if note else ""))
            print_attributes(obj, indent)
            print_tree(obj, depth + 1)
        else:
            print(f"{indent}{name}  {describe_dataset(obj)}")
            print_attributes(obj, indent)


def summarise(path):
    with narrows_h5.open_h5(path) as f:
        print(f"{path}  ({os.path.getsize(path)} bytes)")
        print_attributes(f, "")
        print_tree(f, 1)


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) >= 2 else 2
    for i, path in enumerate(argv[1:]):
        narrows_h5.open_h5(path).close()  # missing or not HDF5: one line, exit 2
        if i:
            print()
        summarise(path)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(narrows_h5.run_tool("h5summary", main, sys.argv))
    except BrokenPipeError:
        sys.exit(0)
