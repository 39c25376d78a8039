# SPDX-License-Identifier: Apache-2.0
"""Analysis without a device: recordings from files or arrays (docs/python.md).

    import palp.analyze
    summary = palp.analyze.indentation("results/solid-p3/indentation.csv")
    summary["k_linear_N_per_mm"], summary["E_star_hertz_Pa"]

The results are the SDK's own JSON, so the keys are those of `palpctl analyze ... --json`.
"""

from __future__ import annotations

import os
from typing import Any, Mapping, Optional, Union

from . import _palp

RecordingLike = Union[str, "os.PathLike[str]", _palp.Recording, Mapping[str, Any]]


def recording(source: RecordingLike) -> _palp.Recording:
    """A recording from a file path (CSV, with its sidecar), a palp.Recording, or a mapping of
    columns named as in a recording file (t_s, i_A, z_mm required; lab units)."""
    if isinstance(source, _palp.Recording):
        return source
    if isinstance(source, (str, os.PathLike)):
        return _palp.read_recording(os.fspath(source))
    if isinstance(source, Mapping):
        return _palp.Recording(dict(source))
    raise _palp.ConfigError(
        f"a recording is a path, a palp.Recording or a mapping of columns, not {type(source).__name__}")


def indentation(source: RecordingLike, params: Optional[_palp.IndentationParams] = None) -> dict:
    """The quasi-static indentation analysis of a recording: the dict `palpctl analyze
    indentation --json` prints (its "params" without "input" and "kf_table")."""
    return _palp._analyze_indentation(recording(source), params if params is not None else _palp.IndentationParams())


def pressure(source: RecordingLike, params: Optional[_palp.IndentationParams] = None) -> dict:
    """The pressure-force test of a recording (paper §V-D): each pressure column it has against
    the object force on the loading branches, with the contact point of its indentation
    analysis. The dict `palpctl analyze pressure --json` prints (contact_point_mm, n_loading,
    channels [{channel, slope_Pa_per_N, r2, rise_Pa, hysteresis_ratio, ...}], params), without
    its "force" text and the "params" keys "input" and "kf_table"; the same as an indentation
    run's summary()["pressure"]. palp.DataError when the recording has no pressure column or no
    contact point."""
    return _palp._analyze_pressure(recording(source),
                                   params if params is not None else _palp.IndentationParams())


def sweep(source: RecordingLike) -> dict:
    """A recording palp.identify (or `palpctl sweep`) wrote, analysed again: the frequency
    response's second-order fit as the SDK's sweep_summary_json (omega_n_rad_per_s, zeta,
    k_N_per_mm, ...), or {"analysis_reason": ...} when the data give none."""
    return _palp._analyze_sweep(recording(source))


def to_pandas(source: RecordingLike):
    """A recording's columns as a pandas.DataFrame (pandas must be installed)."""
    try:
        import pandas
    except ImportError as e:
        raise ImportError("palp.analyze.to_pandas needs pandas (apt install python3-pandas)") from e
    return pandas.DataFrame(recording(source).columns)
