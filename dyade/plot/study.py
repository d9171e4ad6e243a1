"""A design study's figures (``dyade plot study``): an output against one parameter
(one line per combination of the others) or two (a map), a histogram per output with
its limit, the sensitivity bars, and the Pareto front with the chosen design."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from dyade.plot import canvas

LIMITS = {"joint_force": ("_peak", "joint force limit"),
          "transmission_deg": ("_min_deg", "transmission limit")}


def label(result, name: str) -> str:
    unit = result.units.get(name, "")
    return f"{name} [{unit}]" if unit and unit != "-" else name


def given(result) -> np.ndarray:
    """(n,) bool: the variants with outputs (ok or locks)."""
    status = result.columns()["status"]
    return (status == "ok") | (status == "locks")


def versus(result, output: str, x: str, y: str | None = None, fig: Figure | None = None
           ) -> Figure:
    """``output`` against parameter ``x`` (one line per combination of the other
    parameters, failed variants as crosses on the axis) or, with ``y``, a map over
    ``x`` and ``y``."""
    cols = result.columns()
    ok = given(result)
    with canvas.style():
        fig = canvas.new(7.0, 5.0, fig)
        ax = fig.add_subplot()
        if y is None:
            others = [p.key for p in result.spec.free if p.key != x]  # linked ones follow
            keys = [tuple(cols[p][i] for p in others) for i in range(len(ok))]
            for k, key in enumerate(dict.fromkeys(keys)):
                rows = np.array([i for i, other in enumerate(keys) if other == key])
                order = rows[np.argsort(cols[x][rows])]
                name = ", ".join(f"{p} = {v if isinstance(v, str) else format(v, 'g')}"
                                 for p, v in zip(others, key))  # (a choice: its name)
                ax.plot(cols[x][order], np.where(ok[order], cols[output][order], np.nan),
                        **canvas.line(k, marker=True, label=name or None))
                if len(dict.fromkeys(keys)) > 7:
                    break
            failed = ~ok
            if failed.any():
                ax.plot(cols[x][failed], np.full(failed.sum(), np.nanmin(
                    np.where(ok, cols[output], np.nan))), "x", color=canvas.GREY,
                        label="no result (see status)")
            ax.set_xlabel(label(result, x))
            ax.set_ylabel(label(result, output))
            if others or failed.any():
                ax.legend(fontsize="small")
        else:
            xs, ys = np.unique(cols[x]), np.unique(cols[y])
            grid = np.full((ys.size, xs.size), np.nan)
            for i in np.flatnonzero(ok):
                grid[np.searchsorted(ys, cols[y][i]), np.searchsorted(xs, cols[x][i])] = \
                    cols[output][i]
            mesh = ax.pcolormesh(xs, ys, grid, shading="nearest", cmap="viridis")
            if min(xs.size, ys.size) >= 4 and np.isfinite(grid).sum() > 8:
                # on a coarser grid the contours crowd into a cell or two and their
                # labels overlap; the colour bar gives the values
                lines = ax.contour(xs, ys, grid, levels=MaxNLocator(5).tick_values(
                                   np.nanmin(grid), np.nanmax(grid))[1:-1], colors="white",
                                   linewidths=0.7)
                ax.clabel(lines, fontsize="small")
            fig.colorbar(mesh, ax=ax, label=label(result, output))
            ax.set_xlabel(label(result, x))
            ax.set_ylabel(label(result, y))
        ax.set_title(f"{output}: {result.spec.label}")
    return fig


def limit_at(limits: dict, name: str, values: np.ndarray) -> float | None:
    """Where the study's limit on output ``name`` is drawn (a peak force's on the side of
    its values), or None."""
    for key, (suffix, _) in LIMITS.items():
        if key in limits and name.endswith(suffix):
            limit = float(limits[key])
            return limit if suffix != "_peak" or not values.size or values.mean() >= 0 \
                else -limit
    return None


def histograms(result, outputs: list[str], fig: Figure | None = None) -> Figure:
    """A histogram of each output over the variants, with its mean, the 5 % and 95 %
    percentiles and the study's limit where one applies; the outputs constant over the
    variants (``questions.constant``: one value to rounding) are not drawn as
    histograms of round-off but named with their one value under the title."""
    from dyade.study.entry import failure
    from dyade.study.questions import constant

    cols, ok = result.columns(), given(result)
    limits = result.spec.tolerance
    same = [name for name in outputs if constant(cols[name][ok])]
    drawn_outputs = [name for name in outputs if name not in same]
    rows, columns = canvas.grid(max(len(drawn_outputs), 1))
    with canvas.style():
        fig = canvas.new(3.6 * columns, 2.8 * rows + 0.3 * bool(same), fig)
        for k, name in enumerate(drawn_outputs):
            ax = fig.add_subplot(rows, columns, k + 1)
            values = cols[name][ok & np.isfinite(cols[name])]
            bins = max(5, min(40, int(np.sqrt(values.size))))
            drawn = limit_at(limits, name, values)
            ax.hist(values, bins=bins, color=canvas.COLOURS[2], alpha=0.7)
            if values.size:
                for q, style in ((5, ":"), (95, ":")):
                    ax.axvline(np.percentile(values, q), color="black", linestyle=style,
                               linewidth=0.8)
                ax.axvline(values.mean(), color="black", linewidth=0.8)
            for key, (suffix, words) in LIMITS.items():
                if key in limits and name.endswith(suffix):
                    ax.axvline(drawn, color=canvas.COLOURS[1], linewidth=1.5, label=words)
                    canvas.legend_above(ax, fontsize="x-small")
            ax.set_xlabel(label(result, name), fontsize="small")
            ax.set_ylabel("variants", fontsize="small")
            # few ticks, no offset: 0.99925 beside 0.99950 crowds, '+3.999e2' puzzles
            ax.xaxis.set_major_locator(MaxNLocator(4))
            ax.ticklabel_format(axis="x", useOffset=False)
        share = result.tolerance["probability"] if result.tolerance else {}
        words = ", ".join(f"P({failure(k, limits)}) = {v:.3g}" for k, v in share.items())
        title = (f"{result.spec.label}: {int(ok.sum())} of {ok.size} variants give "
                 f"results (mean solid, 5 %/95 % dotted)\n{words}")
        if same:
            values = ", ".join(
                f"{name} = {float(np.median(cols[name][ok & np.isfinite(cols[name])])):.6g}"
                f"{' ' + result.units.get(name, '') if result.units.get(name, '') not in ('', '-') else ''}"
                for name in same)
            title += f"\nconstant over the variants: {values}"
        if not drawn_outputs:
            ax = fig.add_subplot()
            ax.set_axis_off()
            ax.text(0.5, 0.5, "every output asked is constant over the variants",
                    ha="center", va="center", transform=ax.transAxes)
        fig.suptitle(title, fontsize="small")
    return fig


def sensitivity_bars(result, outputs: list[str], fig: Figure | None = None) -> Figure:
    """Normalised sensitivities (% output per % parameter), one panel per output."""
    rows_, columns = canvas.grid(len(outputs))
    table = result.sensitivity
    with canvas.style():
        fig = canvas.new(3.8 * columns, 0.6 + 0.35 * len(result.parameters) * rows_ + 1.2 * rows_,
                         fig)
        for k, name in enumerate(outputs):
            ax = fig.add_subplot(rows_, columns, k + 1)
            rows = [r for r in table if r["output"] == name]
            values = [r["normalised"] for r in rows]
            ax.barh(range(len(rows)), values,
                    color=[canvas.COLOURS[2] if v >= 0 else canvas.COLOURS[1] for v in values])
            ax.set_yticks(range(len(rows)), [r["parameter"] for r in rows], fontsize="small")
            ax.axvline(0.0, color="black", linewidth=0.8)
            ax.set_title(name, fontsize="small")
            ax.set_xlabel("% per %", fontsize="small")
            if not np.isfinite(values).any():  # an output numerically zero: no % per %
                ax.text(0.5, 0.5, "numerically zero at the nominal:\nno % per %",
                        ha="center", va="center", fontsize="small", transform=ax.transAxes,
                        bbox={"facecolor": "white", "edgecolor": "none"})
        fig.suptitle(f"{result.spec.label}: normalised sensitivity (central differences)",
                     fontsize="small")
    return fig


def pareto_front(result, fig: Figure | None = None) -> Figure:
    """The first two objectives of every feasible variant, the non-dominated ones
    joined, and the chosen design (nearest to the ideal point, objectives scaled to
    their range on the front) marked."""
    cols = result.columns()
    (a, sa), (b, sb) = result.spec.optimise["objectives"][:2]
    ok = given(result)
    front = result.pareto
    with canvas.style():
        fig = canvas.new(6.5, 5.0, fig)
        ax = fig.add_subplot()
        ax.plot(cols[a][ok & ~front], cols[b][ok & ~front], "o", color=canvas.GREY,
                markersize=3, label="variants")
        order = np.flatnonzero(front)[np.argsort(cols[a][front])]
        ax.plot(cols[a][order], cols[b][order], "o-", color=canvas.COLOURS[1], markersize=4,
                label="Pareto front")
        chosen = chosen_design(result)
        if chosen is not None:
            ax.plot(cols[a][chosen], cols[b][chosen], "*", color=canvas.COLOURS[2],
                    markersize=14, label=f"chosen: variant {cols['variant'][chosen]}")
        ax.set_xlabel(f"{label(result, a)} ({'min' if sa > 0 else 'max'})")
        ax.set_ylabel(f"{label(result, b)} ({'min' if sb > 0 else 'max'})")
        ax.legend(fontsize="small")
        ax.set_title(f"{result.spec.label}: {int(front.sum())} non-dominated of "
                     f"{int(ok.sum())} variants")
    return fig


def chosen_design(result) -> int | None:
    """The variant of the front nearest the ideal point (each objective scaled to its
    range on the front)."""
    cols, front = result.columns(), result.pareto
    index = np.flatnonzero(front)
    if not index.size:
        return None
    scaled = []
    for name, sense in result.spec.optimise["objectives"]:
        values = sense * cols[name][index]
        span = values.max() - values.min()
        scaled.append((values - values.min()) / (span if span > 0 else 1.0))
    return int(index[np.argmin(np.hypot.reduce(scaled, axis=0) if len(scaled) > 1
                               else scaled[0])])


def question_figure(result, outputs=None, x: str | None = None, y: str | None = None,
                    fig: Figure | None = None) -> Figure:
    """The figure of a study's question: a tolerance study's histograms with their
    limits, a sensitivity study's bars, the Pareto front of several objectives;
    otherwise ``outputs[0]`` (default M_drive_rms, else the first output) against the
    parameter ``x`` (default the first), or a map over ``x`` and ``y``.

    Parameters
    ----------
    result : Study
        From ``dyade.study.study``.
    outputs : list of str, optional
        The outputs to draw (default: every one for histograms and bars).
    x, y : str, optional
        Parameters (their --set key paths) along the axes.
    fig : Figure, optional
        A figure to draw on (default: a new one).

    Examples
    --------
    >>> import dyade.study
    >>> from dyade.plot import study as figures
    >>> result = dyade.study.study("mechanisms/studies/press-slide-tolerance.toml")
    >>> fig = figures.question_figure(result, ["M_drive_rms", "FN_1_4_peak", "stroke_1_4"])
    >>> [ax.get_xlabel() for ax in fig.axes]  # the stroke is constant: named, not drawn
    ['M_drive_rms [N·m]', 'FN_1_4_peak [N]']
    """
    chosen = list(outputs or []) or None
    if result.tolerance is not None:
        return histograms(result, chosen or result.outputs, fig=fig)
    if result.sensitivity is not None:
        return sensitivity_bars(result, chosen or result.outputs, fig=fig)
    if result.pareto is not None and len(result.spec.optimise["objectives"]) > 1:
        return pareto_front(result, fig=fig)
    what = (chosen or ["M_drive_rms" if "M_drive_rms" in result.outputs
                       else result.outputs[0]])[0]
    return versus(result, what, x or result.parameters[0], y, fig=fig)
