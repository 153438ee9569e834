"""The thermal balance of an operating map (``rollerdyn study map --heat-dissipation``).

A bearing runs at the temperature at which it gives off the heat its friction makes. Its
friction power P(T) [W] comes from the map: at each oil temperature T of the grid, the
steady friction torque times the ring speed (:mod:`.steady`: the window's mean power
loss). What it gives off is taken proportional to its temperature above the
surroundings, Q(T) = W_s (T - T_amb), with W_s [W/K] the heat dissipation through the
shaft and the housing (the linear law of ISO 15312's heat balance, where W_s =
q_r A_r / (70 - 20 K) at the reference heat flow density q_r through the bearing's seat
area A_r; docs/study.md, "The thermal balance"), plus what a circulating oil carries
away, rho c_p V (T - T_in): the oil flow V enters at T_in and leaves at the bearing's
temperature, its density rho and its specific heat c_p taken at T_in (c_p by Cragoe's
formula for petroleum oils, :func:`oil_specific_heat`). Both are linear in T, so
Q(T) = W (T - T_ref) with W = W_s + rho c_p V and T_ref = (W_s T_amb + rho c_p V T_in) / W.

For each speed and loads of the map, the balance temperature T* solves P(T) = Q(T) on
the first interval [T_i, T_i+1] of the map's temperatures where P - Q changes sign from
+ to -: a stable balance (a bearing warmer than T* gives off more than it makes, and
cools). Between two temperatures P is interpolated exponentially,
P(T) = P_i (P_i+1 / P_i)^s with s = (T - T_i) / (T_i+1 - T_i), as the friction of oil
films follows the viscosity, which the Vogel law makes nearly exponential in T over tens
of kelvin (B1 without axial load at 3000 rpm: 9.8 W at 60 degC, 3.3 W at 100 degC);
linearly where P is not positive at both ends. T* is then the root of P - Q in s,
found by bisection to 1e-12 of the interval.
The same balance of the quasi-static estimate beside each point (:mod:`.estimates`, the
friction of steady rolling) is the table's ``steady rolling balance [degC]`` (NaN where it
lies outside the map's temperatures): what a quasi-static tool would predict.
Where P - Q is negative already at the lowest temperature, the balance lies below the
map; where it is positive still at the highest, above it (or the bearing runs away
thermally); neither is extrapolated. The oil is taken at the bearing's temperature (one
temperature for the whole bearing, as in the dynamic model).

Over two or more speeds, with a permissible temperature T_perm, the thermally permissible
speed of each loads is the lowest speed at which the balance reaches T_perm (the idea of
DIN 732's thermally permissible speed, with the map's friction instead of the standard's
formulas): on the first interval of the map's speeds where T* - T_perm changes sign from
- to +, T* interpolated linearly in the speed. A balance outside the map's temperatures
still tells on which side of T_perm it lies where T_perm is inside them; where it is
needed for the interpolation, the speed is only bracketed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..config.base import T0_CELSIUS
from ..units import QuantityError, parse_quantity
from .estimates import STEADY_ROLLING
from .maps import RPM, in_unit
from .runs import StudyError

#: The speed and loads that make one balance (the map's axes other than temperature).
GROUP = ("speed [rpm]", "radial_load [N]", "axial_load [N]")

#: Statuses of a balance.
BALANCED, BELOW, ABOVE, NO_VALUE = "balanced", "below the map", "above the map", "no value"

#: Statuses of a thermally permissible speed.
FOUND, BRACKETED, FASTER, SLOWER, UNKNOWN = (
    "found",
    "bracketed",
    "above the map's speeds",
    "below the map's speeds",
    "undetermined",
)

#: The balance's column of the quasi-static estimate: the temperature at which the
#: friction power of steady rolling (:mod:`.estimates`) equals the heat given off.
STEADY_ROLLING_BALANCE = "steady rolling balance [degC]"

#: The balance's table as printed and on the map's page (the note last): column,
#: heading, number format.
THERMAL_COLUMNS = (
    ("speed [rpm]", "speed [rpm]", ".4g"),
    ("radial_load [N]", "F_r [N]", ".4g"),
    ("axial_load [N]", "F_a [N]", ".4g"),
    ("status", "balance", ""),
    ("balance temperature [degC]", "T [degC]", ".4g"),
    (STEADY_ROLLING_BALANCE, "T, steady rolling [degC]", ".4g"),
    ("friction power [W]", "friction power [W]", ".4g"),
    ("torque [N*m]", "torque [N*m]", ".4g"),
    ("temperatures [degC]", "map's T [degC]", ""),
    ("note", "note", ""),
)

#: The thermally permissible speeds' table, as :data:`THERMAL_COLUMNS`.
PERMISSIBLE_COLUMNS = (
    ("radial_load [N]", "F_r [N]", ".4g"),
    ("axial_load [N]", "F_a [N]", ".4g"),
    ("status", "permissible speed", ""),
    ("permissible speed [rpm]", "speed [rpm]", ".4g"),
    ("permissible temperature [degC]", "at [degC]", ".4g"),
    ("speeds [rpm]", "map's speeds [rpm]", ""),
    ("note", "note", ""),
)


@dataclass(frozen=True)
class Dissipation:
    """How the bearing gives off heat (see the module's doc): W_s [W/K] above ``ambient``
    [K], and ``oil_rate`` = rho c_p V [W/K] of a circulating oil entering at ``oil_inlet``
    [K]; ``permissible`` [K] for the thermally permissible speed, or None."""

    conductance: float
    ambient: float
    oil_rate: float = 0.0
    oil_inlet: float = math.nan
    permissible: float | None = None

    @property
    def total(self) -> float:
        """W = W_s + rho c_p V [W/K]."""
        return self.conductance + self.oil_rate

    @property
    def reference(self) -> float:
        """T_ref [K], at which nothing is given off."""
        if self.oil_rate == 0.0:
            return self.ambient
        return (self.conductance * self.ambient + self.oil_rate * self.oil_inlet) / self.total

    def describe(self) -> str:
        """The dissipation in words (a figure's legend, the page)."""
        text = f"{self.conductance:g} W/K above {self.ambient - T0_CELSIUS:g} degC"
        if self.oil_rate:
            text += (
                f" + oil {self.oil_rate:.4g} W/K above its inlet "
                f"{self.oil_inlet - T0_CELSIUS:g} degC"
            )
        return text


def oil_specific_heat(temperature: float, rho_15: float) -> float:
    """Specific heat [J/(kg K)] of a petroleum oil of density ``rho_15`` [kg/m^3] at 15
    degC, at ``temperature`` [K]: Cragoe (US Bureau of Standards, Misc. Publ. 97, 1929),
    c = (0.388 + 0.00045 t) / sqrt(d) Btu/(lb degF) with t in degF and d the specific
    gravity at 60 degF, taken as rho_15 / 999 kg/m^3 (about 1.685 + 0.00339 t[degC]
    kJ/(kg K) over sqrt(d)). FVA 3 at 60 degC: 2.00 kJ/(kg K)."""
    t_f = 1.8 * (temperature - T0_CELSIUS) + 32.0
    return BTU_PER_LB_F * (0.388 + 0.00045 * t_f) / math.sqrt(rho_15 / 999.0)


#: 1 Btu/(lb degF) in J/(kg K) (international table Btu).
BTU_PER_LB_F = 4186.8


def friction_power(rows, torque: str = "torque [N*m]") -> np.ndarray:
    """The friction power [W] of map rows: the steady torque (or the column ``torque``:
    the quasi-static estimate's) times the ring speed; NaN where a row lacks it."""
    if torque not in rows:  # a table written before the estimate
        return np.full(len(rows), math.nan)
    values = np.asarray(rows[torque], dtype=float)
    return values * np.asarray(rows["speed [rpm]"], dtype=float) * RPM


def balance(
    temperatures: np.ndarray, power: np.ndarray, conductance: float, ambient: float
) -> tuple[str, float, float]:
    """(status, T* [K], P(T*) [W]) of the friction ``power`` [W] at ``temperatures`` [K]
    (ascending, finite values only) against the dissipation ``conductance`` (T -
    ``ambient``): see the module's doc. NaN for T* and P outside the map."""
    if len(temperatures) < 2:
        return NO_VALUE, math.nan, math.nan
    surplus = power - conductance * (temperatures - ambient)
    if surplus[0] <= 0.0:
        return BELOW, math.nan, math.nan
    for i in range(len(surplus) - 1):
        if surplus[i] > 0.0 >= surplus[i + 1]:
            t0, t1 = temperatures[i], temperatures[i + 1]
            p = _interpolant(power[i], power[i + 1])
            lo, hi = 0.0, 1.0  # P - Q > 0 at lo, <= 0 at hi
            while hi - lo > 1e-12:
                mid = 0.5 * (lo + hi)
                if p(mid) - conductance * (t0 + mid * (t1 - t0) - ambient) > 0.0:
                    lo = mid
                else:
                    hi = mid
            s = 0.5 * (lo + hi)
            return BALANCED, t0 + s * (t1 - t0), p(s)
    return ABOVE, math.nan, math.nan


def _interpolant(p0: float, p1: float):
    """P(s) between P(0) = ``p0`` and P(1) = ``p1``: exponential where both are positive,
    else linear (see the module's doc)."""
    if p0 > 0.0 and p1 > 0.0:
        ratio = p1 / p0
        return lambda s: p0 * ratio**s
    return lambda s: p0 + s * (p1 - p0)


def balance_temperatures(frame, dissipation: Dissipation):
    """One row per speed and loads of the map ``frame`` (the rows of
    :func:`.maps.point_row`, with ``temperature [degC]``): the balance's status, its
    temperature [degC], friction power [W] and torque [N*m], the dissipation, the map's
    temperatures it used, and a note (why there is none; the points not steady it rests
    on)."""
    import pandas as pd

    rows = []
    conductance, reference = dissipation.total, dissipation.reference
    for key, group in frame.groupby(list(GROUP), sort=True):
        group = group.sort_values("temperature [degC]")
        power = friction_power(group)
        ok = np.isfinite(power)
        temps = np.asarray(group["temperature [degC]"], dtype=float)[ok] + T0_CELSIUS
        status, t_star, p_star = balance(temps, power[ok], conductance, reference)
        speed = float(key[0]) * RPM
        estimate = friction_power(group, STEADY_ROLLING)
        known = np.isfinite(estimate)
        quasi_status, quasi_t, _ = balance(
            np.asarray(group["temperature [degC]"], dtype=float)[known] + T0_CELSIUS,
            estimate[known],
            conductance,
            reference,
        )
        notes = (
            _note(status, temps, power[ok], conductance, reference, group),
            _estimate_note(quasi_status),
        )
        row = dict(zip(GROUP, key, strict=True))
        row.update(
            {
                "status": status,
                "balance temperature [degC]": t_star - T0_CELSIUS,
                # NaN where that balance lies outside the map's temperatures too
                STEADY_ROLLING_BALANCE: quasi_t - T0_CELSIUS,
                "friction power [W]": p_star,
                "torque [N*m]": p_star / speed if speed > 0 else math.nan,
                "heat dissipation [W/K]": dissipation.conductance,
                "ambient [degC]": dissipation.ambient - T0_CELSIUS,
                "oil [W/K]": dissipation.oil_rate,
                "oil inlet [degC]": dissipation.oil_inlet - T0_CELSIUS,
                "temperatures [degC]": ", ".join(f"{t - T0_CELSIUS:g}" for t in temps),
                "lowest temperature [degC]": _in_celsius(temps, np.min),
                "highest temperature [degC]": _in_celsius(temps, np.max),
                "note": "; ".join(text for text in notes if text),
            }
        )
        rows.append(row)
    return pd.DataFrame(rows)


def _in_celsius(temps: np.ndarray, pick) -> float:
    """``pick`` (min or max) of ``temps`` [K] in degC; NaN for none."""
    return float(pick(temps)) - T0_CELSIUS if len(temps) else math.nan


def _note(status: str, temps, power, conductance: float, reference: float, group) -> str:
    """Why a balance is outside the map or missing, and which points it rests on that are
    not steady."""
    from .maps import STEADY

    def at(i: int) -> str:
        given = conductance * (temps[i] - reference)
        return (
            f"at {temps[i] - T0_CELSIUS:g} degC the friction makes {power[i]:.4g} W and "
            f"{conductance:g} W/K give off {given:.4g} W"
        )

    if status == NO_VALUE:
        return f"friction at {len(temps)} temperature(s) of the map; the balance needs two"
    if status == BELOW:
        note = f"{at(0)}: the bearing runs cooler than the map's lowest temperature"
    elif status == ABOVE:
        note = (
            f"{at(len(temps) - 1)}: the bearing runs hotter than the map's highest "
            "temperature (or runs away thermally)"
        )
    else:
        note = ""
    unsteady = group[group["status"] != STEADY]
    if len(unsteady):
        listed = ", ".join(f"{t:g}" for t in unsteady["temperature [degC]"])
        more = f"points not steady at {listed} degC"
        note = f"{note}; {more}" if note else more
    return note


def _estimate_note(status: str) -> str:
    """Where the quasi-static estimate's balance lies when not within the map ("" when it
    is, or when there is no estimate)."""
    if status in (BELOW, ABOVE):
        return f"steady rolling (quasi-static): {status}"
    return ""


def _side(row, permissible: float) -> tuple[float, float]:
    """(sign of T* - ``permissible`` [degC]: -1, +1 or NaN where unknown; T* [degC] or
    NaN) of a row of the balance table."""
    if row["status"] == BALANCED:
        t = float(row["balance temperature [degC]"])
        return (1.0 if t > permissible else -1.0), t
    if row["status"] == BELOW and permissible >= row["lowest temperature [degC]"]:
        return -1.0, math.nan
    if row["status"] == ABOVE and permissible <= row["highest temperature [degC]"]:
        return 1.0, math.nan
    return math.nan, math.nan


def permissible_speeds(thermal, permissible: float):
    """One row per loads of the balance table ``thermal`` (:func:`balance_temperatures`):
    the thermally permissible speed [rpm] at which the balance reaches ``permissible``
    [degC] (see the module's doc), its status, the speeds that bracket it and a note."""
    import pandas as pd

    rows = []
    for key, group in thermal.groupby(list(GROUP[1:]), sort=True):
        group = group.sort_values("speed [rpm]")
        speeds = np.asarray(group["speed [rpm]"], dtype=float)
        sides = [_side(row, permissible) for _, row in group.iterrows()]
        status, speed, low, high = _crossing(speeds, sides, permissible)
        row = dict(zip(GROUP[1:], key, strict=True))
        row.update(
            {
                "status": status,
                "permissible speed [rpm]": speed,
                "from [rpm]": low,
                "to [rpm]": high,
                "permissible temperature [degC]": permissible,
                "speeds [rpm]": ", ".join(f"{v:g}" for v in speeds),
                "note": _speed_note(status, low, high, permissible),
            }
        )
        rows.append(row)
    return pd.DataFrame(rows)


def _crossing(speeds: np.ndarray, sides, permissible: float):
    """(status, speed, bracket's low and high speed) of the first change of T* - T_perm
    from - to + over ``speeds`` (``sides``: (sign, T*) per speed, :func:`_side`)."""
    if len(sides) and sides[0][0] > 0:
        return SLOWER, math.nan, math.nan, float(speeds[0])
    for i in range(len(speeds) - 1):
        (a, ta), (b, tb) = sides[i], sides[i + 1]
        if math.isnan(a):  # what lies beyond an unknown side is unknown
            return UNKNOWN, math.nan, math.nan, math.nan
        if a < 0 < b:
            n0, n1 = float(speeds[i]), float(speeds[i + 1])
            if math.isfinite(ta) and math.isfinite(tb):
                return FOUND, n0 + (permissible - ta) / (tb - ta) * (n1 - n0), n0, n1
            return BRACKETED, math.nan, n0, n1
    if len(sides) and all(sign < 0 for sign, _ in sides):
        return FASTER, math.nan, float(speeds[-1]), math.nan
    return UNKNOWN, math.nan, math.nan, math.nan


def _speed_note(status: str, low: float, high: float, permissible: float) -> str:
    """Why a thermally permissible speed is not a number."""
    if status == SLOWER:
        return f"the balance is above {permissible:g} degC already at {high:g} rpm"
    if status == FASTER:
        return f"the balance stays below {permissible:g} degC up to {low:g} rpm"
    if status == BRACKETED:
        return (
            f"between {low:g} and {high:g} rpm; a balance there lies outside the map's "
            "temperatures, so no value is interpolated"
        )
    if status == UNKNOWN:
        return (
            "a balance outside the map's temperatures (or none) leaves open on which side "
            f"of {permissible:g} degC it lies; widen --temperature"
        )
    return ""


def write_balance_figure(
    frame, thermal, dissipation: Dissipation, out: Path, name: str
) -> list[Path]:
    """The friction power over the oil temperature for each speed and loads of the map,
    the quasi-static estimate's (dotted), the heat given off (a dashed line) and each
    balance (a star); PNG and SVG in ``out`` as ``thermal_balance``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    t_all = np.asarray(frame["temperature [degC]"], dtype=float)
    for key, group in frame.groupby(list(GROUP), sort=True):
        group = group.sort_values("temperature [degC]")
        label = f"{key[0]:g} rpm, F_r = {key[1]:g} N, F_a = {key[2]:g} N"
        temps, power = np.asarray(group["temperature [degC]"], dtype=float), friction_power(group)
        (line,) = ax.plot(temps, power, "o", label=label)
        for i in range(len(temps) - 1):  # the interpolant the balance solves on
            if np.isfinite(power[i : i + 2]).all():
                s = np.linspace(0.0, 1.0, 21)
                p = _interpolant(power[i], power[i + 1])
                ax.plot(temps[i] + s * (temps[i + 1] - temps[i]), p(s), color=line.get_color())
        for _, row in _rows_of(thermal, GROUP, key, BALANCED).iterrows():
            t, p = row["balance temperature [degC]"], row["friction power [W]"]
            _star(ax, t, p, f"{t:.1f} degC", line.get_color())
        estimate = friction_power(group, STEADY_ROLLING)
        if np.isfinite(estimate).any():  # the quasi-static estimate, dotted
            ax.plot(temps, estimate, ":", marker="s", ms=4, color=line.get_color())
    if STEADY_ROLLING in frame and np.isfinite(friction_power(frame, STEADY_ROLLING)).any():
        ax.plot([], [], ":", marker="s", ms=4, color="0.4", label="steady rolling (quasi-static)")
    t_line = np.linspace(np.nanmin(t_all), np.nanmax(t_all), 50)
    ax.plot(
        t_line,
        dissipation.total * (t_line - (dissipation.reference - T0_CELSIUS)),
        "k--",
        label=f"heat given off: {dissipation.describe()}",
    )
    return _finish(
        fig,
        ax,
        ("oil and bearing temperature [degC]", "power [W]"),
        f"{name}: thermal balance (friction power = heat given off)",
        Path(out) / "thermal_balance",
    )


def write_speed_figure(thermal, speeds, permissible: float, out: Path, name: str) -> list[Path]:
    """The balance temperature over the speed for each loads (balances outside the map
    left out), the permissible temperature (a dashed line) and each thermally permissible
    speed (a star); PNG and SVG in ``out`` as ``thermal_speed``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, group in thermal.groupby(list(GROUP[1:]), sort=True):
        group = group.sort_values("speed [rpm]")
        (line,) = ax.plot(
            group["speed [rpm]"],
            group["balance temperature [degC]"],
            "o-",
            label=f"F_r = {key[0]:g} N, F_a = {key[1]:g} N",
        )
        for _, row in _rows_of(speeds, GROUP[1:], key, FOUND).iterrows():
            n = row["permissible speed [rpm]"]
            _star(ax, n, permissible, f"{n:.0f} rpm", line.get_color())
    ax.axhline(permissible, color="k", ls="--", label=f"permissible, {permissible:g} degC")
    return _finish(
        fig,
        ax,
        ("speed of the turning ring [rpm]", "balance temperature [degC]"),
        f"{name}: thermally permissible speed",
        Path(out) / "thermal_speed",
    )


def _rows_of(table, columns, key, status: str):
    """The rows of ``table`` whose ``columns`` hold ``key`` and whose status is
    ``status``."""
    chosen = table["status"] == status
    for column, value in zip(columns, key, strict=True):
        chosen &= table[column] == value
    return table[chosen]


def _star(ax, x: float, y: float, text: str, color) -> None:
    """A result marked on ``ax``: a star at (x, y) in ``color``, labelled ``text``."""
    ax.plot(x, y, "*", ms=14, color=color)
    ax.annotate(text, (x, y), textcoords="offset points", xytext=(6, 6))


def _finish(fig, ax, labels: tuple[str, str], title: str, path: Path) -> list[Path]:
    """``ax`` labelled (x, y), titled and with its legend; ``fig`` written as
    ``path``.png and .svg."""
    from ..plots import save_figure

    ax.set(xlabel=labels[0], ylabel=labels[1], title=title)
    ax.legend(fontsize="small")
    return save_figure(fig, path.parent, path.name)


def dissipation_from_options(cfg, temperatures: list[float], options: dict):
    """The thermal balance's :class:`Dissipation` from the map's ``options`` (by
    their command-line names), or None without ``--heat-dissipation``. Refuses a
    dissipation or oil flow that is not above 0, the balance's other options without a
    dissipation, an oil inlet without an oil flow, and a balance over fewer than two
    temperatures."""
    given = {k: v for k, v in options.items() if v is not None}
    if "--heat-dissipation" not in given:
        for option, value in given.items():
            raise StudyError(
                f"{option} {value!r}: belongs to the thermal balance, which needs "
                "--heat-dissipation"
            )
        return None
    if "--oil-inlet" in given and "--oil-flow" not in given:
        raise StudyError(
            f"--oil-inlet {given['--oil-inlet']!r}: the temperature of an oil flow, which "
            "needs --oil-flow"
        )
    conductance = _quantity(
        given["--heat-dissipation"], "--heat-dissipation", "thermal conductance", "W/K"
    )
    ambient = _quantity(given.get("--ambient", "20 degC"), "--ambient", "temperature", "degC")
    flow = _quantity(given.get("--oil-flow", 0.0), "--oil-flow", "volume flow", "m^3/s")
    for option, value in (("--heat-dissipation", conductance), ("--oil-flow", flow)):
        if not value > 0 and (option == "--heat-dissipation" or option in given):
            unit = "W/K" if option == "--heat-dissipation" else "m^3/s"
            raise StudyError(f"{option} {given[option]!r}: must be above 0 {unit}")
    if len(temperatures) < 2:
        raise StudyError(
            f"--heat-dissipation {given['--heat-dissipation']!r}: the thermal balance needs "
            "the friction at two or more oil temperatures; give them with --temperature "
            '(e.g. "60,80,100" in degC)'
        )
    inlet = _quantity(
        given.get("--oil-inlet", f"{ambient!r} K"), "--oil-inlet", "temperature", "degC"
    )
    lub = cfg.lubricant
    density = lub.density_at(inlet)
    if flow and not density > 0:
        raise StudyError(
            f"--oil-inlet {given.get('--oil-inlet', given.get('--ambient', '20 degC'))!r}: "
            f"the oil's density there is {density:.4g} kg/m^3 (lubricant.density); it must "
            "be above 0"
        )
    rate = flow * density * oil_specific_heat(inlet, lub.density.rho_15)
    permissible = given.get("--permissible-temperature")
    if permissible is not None:
        text = permissible
        permissible = _quantity(permissible, "--permissible-temperature", "temperature", "degC")
    found = Dissipation(conductance, ambient, rate, inlet if flow else math.nan, permissible)
    # the balance lies above the sinks' temperature (the ambient's and the oil inlet's, by
    # their shares) at any speed that makes heat: a limit at or below it has no speed (an
    # empty figure and exit status 0, before)
    if permissible is not None and not permissible > found.reference:
        raise StudyError(
            f"--permissible-temperature {text!r}: must be above "
            f"{found.reference - T0_CELSIUS:.4g} degC, the temperature of what the bearing's "
            "heat flows to (--ambient, --oil-inlet): no speed keeps it at or below that"
        )
    return found


def _quantity(value: Any, option: str, family: str, unit: str) -> float:
    """``value`` of a map option in SI: a number in ``unit``, or text with its own unit;
    :class:`StudyError` naming ``option`` otherwise."""
    try:
        return parse_quantity(in_unit(value, unit), family)
    except QuantityError as err:
        raise StudyError(f"{option} {value!r}: {err}") from None


def write_thermal(frame, dissipation, out: Path, name: str, figures: list):
    """(thermal balance, permissible speeds) of the map ``frame`` with ``dissipation``
    (a :class:`Dissipation`; None, None without), their tables and figures written in
    ``out`` (the figures appended to ``figures``); what an earlier invocation wrote and
    this one does not is removed."""
    thermal = permissible = None
    if dissipation is not None:
        thermal = balance_temperatures(frame, dissipation)
        thermal.to_csv(out / "thermal.csv", index=False)
        figures += write_balance_figure(frame, thermal, dissipation, out / "figures", name)
        limit = dissipation.permissible
        if limit is not None:
            permissible = permissible_speeds(thermal, limit - T0_CELSIUS)
            permissible.to_csv(out / "thermal_speed.csv", index=False)
            figures += write_speed_figure(
                thermal, permissible, limit - T0_CELSIUS, out / "figures", name
            )
    stale = []
    for table, csv, figure in (
        (thermal, "thermal.csv", "thermal_balance"),
        (permissible, "thermal_speed.csv", "thermal_speed"),
    ):
        if table is None:
            stale += [out / csv, *(out / "figures" / f"{figure}.{e}" for e in ("png", "svg"))]
    for file in stale:
        file.unlink(missing_ok=True)
    return thermal, permissible


__all__ = [
    "Dissipation",
    "balance",
    "dissipation_from_options",
    "balance_temperatures",
    "friction_power",
    "permissible_speeds",
    "write_balance_figure",
    "write_speed_figure",
    "write_thermal",
]
