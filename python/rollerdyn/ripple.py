"""What the rollers' passing makes (not in the paper): the inner ring's vibration and the
friction torque's ripple at the roller pass frequency.

A radial load on a bearing whose rollers pass the load zone one by one is carried by a
roller set that looks different every fraction of a roller pitch: the ring's equilibrium
moves as the set turns, and repeats every pitch. The ring therefore vibrates, and the
friction torque ripples, at the rate at which rollers pass a point of the stationary outer
ring, Z times the roller set's speed, and at its harmonics: the varying compliance
vibration (Sunnersjö, "Varying compliance vibrations of rolling bearings", J. Sound Vib.
58 (1978) 363-373). Its quasi-static size is the ring's displacement over one roller pitch
in the quasi-static analysis (:func:`rollerdyn.statics.statics_sweep` over
``roller_set_phase``); ``docs/dynamics.md``, "Vibration and torque ripple at the roller
pass frequency", compares the two for B1.

Kinematic frequencies of a bearing whose inner ring turns at f_i with the outer ring
fixed, rolling without slip (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., vol. 1,
ch. 8; contact angle 0): roller set f_c = f_i (1 - D/d_m)/2, roller pass on the outer ring
Z f_c, on the inner ring Z (f_i - f_c), roller spin f_i d_m/(2D) (1 - (D/d_m)^2); with the
outer ring turning too, :func:`pass_frequencies`. Where the radial load's direction is
fixed, the ring vibrates at Z f_c whichever ring turns.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import xarray as xr

__all__ = [
    "PassFrequencies",
    "RIPPLE_SIGNALS",
    "amplitude_at",
    "amplitude_spectrum",
    "pass_frequencies",
    "ripple",
]

#: Harmonics of the roller pass frequency :func:`ripple` measures.
HARMONICS = 3

#: Fewest periods of the roller pass frequency in a result's full-speed part for
#: :func:`ripple` to measure its amplitudes: with fewer, the Hann window's main lobe
#: (4 / duration wide) takes in the neighbouring harmonics and the slow drift.
MIN_PERIODS = 6.0

#: What :func:`ripple` measures: name -> (unit, description); ``ring_y`` and ``ring_z``
#: are the components of the result's ``ring_position``.
RIPPLE_SIGNALS = {
    "frictional_torque": ("N*m", "bearing frictional torque"),
    "ring_y": ("m", "inner ring displacement along y (the radial load's line)"),
    "ring_z": ("m", "inner ring displacement along z (across the load)"),
}


@dataclass(frozen=True)
class PassFrequencies:
    """Kinematic frequencies of a bearing [Hz] (the module's doc)."""

    ring: float
    roller_set: float
    outer_pass: float
    inner_pass: float
    roller_spin: float


def pass_frequencies(
    roller_count: int,
    roller_diameter: float,
    pitch_diameter: float,
    ring_speed: float,
    outer_speed: float = 0.0,
) -> PassFrequencies:
    """The kinematic frequencies [Hz] of ``roller_count`` rollers of diameter D on the pitch
    diameter d_m [m], the inner ring turning at ``ring_speed`` and the outer ring at
    ``outer_speed`` [rad/s] (by default fixed): the module's doc, with the roller set at
    f_c = f_i (1 - D/d_m)/2 + f_o (1 + D/d_m)/2 (Harris & Kotzalas, eq. 8.23), ``ring``
    the inner ring's frequency relative to the outer one, the pass frequencies relative
    to each ring. All magnitudes."""
    if not (roller_count >= 1 and 0.0 < roller_diameter < pitch_diameter):
        raise ValueError(
            f"pass_frequencies: {roller_count} rollers of {roller_diameter} m on a pitch "
            f"diameter of {pitch_diameter} m: needs at least one roller and 0 < D < d_m"
        )
    ratio = roller_diameter / pitch_diameter
    f_i = ring_speed / (2.0 * math.pi)
    f_o = outer_speed / (2.0 * math.pi)
    f_c = 0.5 * f_i * (1.0 - ratio) + 0.5 * f_o * (1.0 + ratio)
    f_rel = abs(f_i - f_o)
    return PassFrequencies(
        ring=f_rel,
        roller_set=abs(f_c),
        outer_pass=roller_count * abs(f_c - f_o),
        inner_pass=roller_count * abs(f_i - f_c),
        roller_spin=0.5 * f_rel / ratio * (1.0 - ratio * ratio),
    )


def _detrended(time: np.ndarray, values: np.ndarray) -> np.ndarray:
    """``values`` less their least-squares line over ``time``: a slow drift (a ring that
    floats axially, a torque still settling) would leak into every frequency."""
    slope, offset = np.polyfit(time - time[0], values, 1)
    return values - (offset + slope * (time - time[0]))


def amplitude_at(time, values, frequency: float) -> float:
    """The amplitude of the sinusoid at ``frequency`` [Hz] in ``values`` sampled at ``time``
    [s] (evenly): the Fourier coefficient at that frequency of the detrended values under a
    Hann window, 2|sum w x e^(-i 2 pi f t)| / sum w, exact for a sinusoid whatever the
    number of its periods, up to the leakage of the other components: the window's
    transform, |sinc(d) / (1 - d^2)| of a component d spectral lines (1 / duration) away,
    below 2e-3 of one at least :data:`MIN_PERIODS` lines away."""
    t = np.asarray(time, dtype=float)
    x = _detrended(t, np.asarray(values, dtype=float))
    w = np.hanning(t.size)
    phase = np.exp(-2j * np.pi * frequency * (t - t[0]))
    return float(2.0 * abs(np.sum(w * x * phase)) / np.sum(w))


def amplitude_spectrum(time, values) -> tuple[np.ndarray, np.ndarray]:
    """The one-sided amplitude spectrum of the detrended ``values`` (evenly sampled at
    ``time`` [s]) under a Hann window: (frequencies [Hz], amplitudes), a sinusoid at a
    spectral line showing its amplitude."""
    t = np.asarray(time, dtype=float)
    x = _detrended(t, np.asarray(values, dtype=float))
    w = np.hanning(t.size)
    spectrum = 2.0 * np.abs(np.fft.rfft(w * x)) / np.sum(w)
    return np.fft.rfftfreq(t.size, float(np.mean(np.diff(t)))), spectrum


def _signal(ds: xr.Dataset, name: str) -> np.ndarray:
    if name.startswith("ring_"):
        return np.asarray(ds.ring_position.sel(xyz=name[-1]).values, dtype=float)
    return np.asarray(ds[name].values, dtype=float)


def result_geometry(ds: xr.Dataset) -> tuple[float, float] | None:
    """(roller diameter D, pitch diameter d_m) [m] of the bearing a result records in its
    configuration (``config_resolved``), or None where it records none."""
    from .config import ConfigError, parse_config
    from .provenance import recorded_configuration

    recorded = recorded_configuration(ds.attrs)
    if recorded is None:
        return None
    try:
        g = parse_config(recorded, si_numbers=True).geometry
    except ConfigError:
        return None
    return g.roller_diameter, g.pitch_diameter


def ripple(ds: xr.Dataset, geometry: tuple[float, float] | None = None) -> dict:
    """The ripple of a result at full speed (:func:`rollerdyn.simulation.full_speed`): the
    roller set's frequency [Hz], measured (the rollers' mean orbital speed, where the
    result recorded the rollers) and kinematic (of ``geometry`` = (D, d_m) [m], by default
    the result's own, :func:`result_geometry`); the roller pass frequency Z f_c of the
    measured one (else of the kinematic one); and for each of :data:`RIPPLE_SIGNALS` its
    mean, peak-to-peak and amplitudes at the first :data:`HARMONICS` harmonics (SI). The
    amplitudes are NaN, with a ``note``, where the full-speed part holds fewer than
    :data:`MIN_PERIODS` roller passes, or where the roller set's frequency is known
    neither way."""
    from .simulation import full_speed, recorded, ring_speeds

    part = full_speed(ds)
    t = np.asarray(part.time.values, dtype=float)
    z = int(ds.sizes.get("roller", 0))
    ring_speed, outer_speed = (float(np.mean(s)) for s in ring_speeds(part))
    geometry = geometry if geometry is not None else result_geometry(ds)
    kinematic = math.nan
    if geometry is not None:
        kinematic = pass_frequencies(z, *geometry, ring_speed, outer_speed).roller_set
    measured = math.nan
    if recorded(part, "rollers"):
        measured = abs(float(np.nanmean(part.orbital_speed.values))) / (2.0 * math.pi)
    passing = z * (measured if math.isfinite(measured) else kinematic)
    span = float(t[-1] - t[0]) if t.size > 1 else 0.0
    out: dict = {
        "roller_set_frequency": measured,
        "kinematic_roller_set_frequency": kinematic,
        "roller_pass_frequency": passing,
        "span": span,
        "note": "",
    }
    enough = passing * span >= MIN_PERIODS and t.size >= 8
    if not math.isfinite(passing):
        out["note"] = (
            "no roller pass frequency: the result records neither the rollers nor its configuration"
        )
    elif not enough:
        out["note"] = (
            f"{passing * span:.3g} roller passes at full speed, fewer than {MIN_PERIODS:g}: "
            "no amplitudes (run longer at full speed)"
        )
    for name in RIPPLE_SIGNALS:
        x = _signal(part, name)
        out[f"{name}_mean"] = float(np.mean(x)) if x.size else math.nan
        out[f"{name}_peak_to_peak"] = float(np.ptp(x)) if x.size else math.nan
        for k in range(1, HARMONICS + 1):
            value = amplitude_at(t, x, k * passing) if enough else math.nan
            out[f"{name}_amplitude_{k}"] = value
    return out


def spectra(ds: xr.Dataset) -> dict | None:
    """The amplitude spectra (:func:`amplitude_spectrum`) of :data:`RIPPLE_SIGNALS` over a
    result's full-speed part: ``{"frequency": [Hz], name: amplitudes (SI)}``; None where
    that part has fewer than 8 outputs."""
    from .simulation import full_speed

    part = full_speed(ds)
    t = np.asarray(part.time.values, dtype=float)
    if t.size < 8:
        return None
    out: dict = {}
    for name in RIPPLE_SIGNALS:
        out["frequency"], out[name] = amplitude_spectrum(t, _signal(part, name))
    return out


#: How far the figures draw the spectra: up to this many times the roller pass frequency.
SPECTRUM_REACH = 4.5


def shown_spectra(items) -> tuple[float, list[float], list]:
    """What the ripple figures draw of ``items`` (name, result, its :func:`ripple`): the
    first measured result's roller pass frequency [Hz], its harmonics within the reach,
    and (name, result, :func:`spectra` cut at :data:`SPECTRUM_REACH` times that frequency)
    for each result whose ripple has amplitudes; (NaN, [], []) where none has."""
    measured = [(name, ds, r) for name, ds, r in items if r["note"] == ""]
    if not measured:
        return math.nan, [], []
    passing = measured[0][2]["roller_pass_frequency"]
    top = SPECTRUM_REACH * passing
    cut = []
    for name, ds, _ in measured:
        s = spectra(ds)
        keep = s["frequency"] <= top
        cut.append((name, ds, {k: v[keep] for k, v in s.items()}))
    harmonics = [k * passing for k in range(1, int(SPECTRUM_REACH) + 1)]
    return passing, harmonics, cut


#: The report's and the command line's rows of :func:`ripple`: (key, text, unit, factor
#: from SI).
RIPPLE_ROWS = (
    ("roller_set_frequency", "roller set, simulated (rollers' mean orbital speed)", "Hz", 1.0),
    ("kinematic_roller_set_frequency", "roller set, kinematic (rolling without slip)", "Hz", 1.0),
    ("roller_pass_frequency", "roller pass frequency Z f_c", "Hz", 1.0),
    ("frictional_torque_mean", "frictional torque, mean", "N·m", 1.0),
    *(
        (
            f"frictional_torque_amplitude_{k}",
            f"frictional torque, amplitude at {k} Z f_c",
            "N·m",
            1.0,
        )
        for k in range(1, HARMONICS + 1)
    ),
    *(
        (
            f"ring_{axis}_amplitude_{k}",
            f"inner ring along {axis}, amplitude at {k} Z f_c",
            "nm",
            1e9,
        )
        for axis in ("y", "z")
        for k in range(1, HARMONICS + 1)
    ),
)
