"""The linkage drawn from its kinematics: links as bars or plates, sliders on their
guides, frame pivots hatched, and the paths of the named link points.

``geometry(result)`` turns a result's motion into world coordinates of every drawn
element at every reported position (vectorised over the positions); a ``Scene`` puts
them on an axes and moves them to position k (``update``), which both the still figure
(``figure``, several crank angles side by side) and the animation (``dyade.plot.animate``)
use. A link is a bar between its two outermost points when its points lie on a line,
else a plate (their convex hull); its points are its revolute joints, the slider points
it carries, the ends of the guides on it (over the slider's travel) and its named
points. Pins sit at the joint positions of the CSV (``x_i_j``, ``y_i_j``).
"""

from __future__ import annotations

from dyade.plot import require

require()  # before matplotlib: without the plot extra, the install hint

from dataclasses import dataclass

import numpy as np
from matplotlib.figure import Figure

from dyade.linkage.kinematics import joint_point
from dyade.linkage.motion import perp, travel
from dyade.model.mechanism import FRAME, Prismatic, Revolute
from dyade.plot import canvas
from dyade.plot.labels import Placer, leader

BLOCK = (0.09, 0.05)  # block length and height, shares of the mechanism's size [-]
SHORT = 0.45  # [-] a block at most this share of the shortest link: it hides no pin
PIVOT = 0.045  # frame pivot symbol height, share of the mechanism's size [-]
PANEL = 3.6  # [in] one panel of a small linkage
CROWD = 10  # labels (links and named points) a PANEL-wide panel holds
WIDEST = 2.0  # [-] a big linkage's panel at most this many times PANEL wide
LINK_SIZE, POINT_SIZE = 6.5, 7.0  # [pt] font sizes of link numbers and point names


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Body:
    """One moving link's outline over the positions."""

    link: int
    outline: np.ndarray
    """(n, m, 2) world points [m]: a bar (m = 2) or a plate's polygon (m ≥ 3)"""

    @property
    def plate(self) -> bool:
        return self.outline.shape[1] > 2


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Slider:
    """A prismatic joint: the block on the slider link and the two rails of the guide."""

    joint: tuple[int, int]
    carrier: int
    """the link that carries the guide"""
    fixed_guide: bool
    """the guide is on the frame (its rails are hatched)"""
    block: np.ndarray
    """(n, 4, 2) the block's corners [m]"""
    rails: np.ndarray
    """(n, 2, 2, 2) two rails, each from one end to the other [m]"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class Geometry:
    """Everything to draw, at each position drawn (axis 0)."""

    crank_angle: np.ndarray
    """(n,) [rad]"""
    bodies: list[Body]
    sliders: list[Slider]
    pins: dict[tuple[int, int], np.ndarray]
    """revolute joint -> (n, 2) position [m] (as the CSV's x_i_j, y_i_j)"""
    pivots: dict[tuple[int, int], np.ndarray]
    """revolute joints with the frame -> (2,) position [m]"""
    points: dict[str, np.ndarray]
    """named link point -> (n, 2) position [m]"""
    paths: dict[str, np.ndarray]
    """named link point -> (m, 2) its path over the whole sweep [m]"""
    size: float
    """[m] the diagonal of the sweep's joints and points: the scale of the symbols"""
    limits: tuple[float, float, float, float]
    """x min, x max, y min, y max [m] of everything over the sweep, with a margin"""


@dataclass(slots=True, eq=False)  # holds arrays: no meaningful ==
class _Layout:
    """What is drawn, in link coordinates, sized from the sweep."""

    outlines: dict[int, np.ndarray]
    """moving link -> (m, 2) its bar ends or plate polygon in its frame [m]"""
    guides: list[tuple[Prismatic, tuple]]
    """prismatic joint -> the guide's two ends in the carrier's frame [m]"""
    block: tuple[float, float]
    """block length and height [m]"""
    size: float


def _hull(points: np.ndarray) -> np.ndarray:
    """Indices of the convex hull of 2-D points, counter-clockwise (Andrew's monotone
    chain); two indices (the extremes) when they lie on a line."""
    order = np.lexsort((points[:, 1], points[:, 0]))
    scale = float(np.ptp(points, axis=0).max()) or 1.0

    def half(indices) -> list[int]:
        chain: list[int] = []
        for k in indices:
            while len(chain) >= 2:
                o, a, b = points[chain[-2]], points[chain[-1]], points[k]
                turn = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
                if turn > 1e-12 * scale ** 2:
                    break
                chain.pop()
            chain.append(int(k))
        return chain

    hull = half(order)[:-1] + half(order[::-1])[:-1]
    return np.array(hull) if len(hull) > 2 else np.array([order[0], order[-1]])


def _unique(points: list) -> np.ndarray:
    out: list[tuple[float, float]] = []
    for p in points:
        if not any(np.hypot(p[0] - q[0], p[1] - q[1]) < 1e-9 for q in out):
            out.append((float(p[0]), float(p[1])))
    return np.array(out).reshape(-1, 2)


def _layout(result) -> _Layout:
    """Each link's points in its frame, the guides over the sliders' travel, and the
    scale."""
    mechanism, motion, rows = result.mechanism, result.kinematics.motion, result.rows
    local = {link: list(data.points.values()) for link, data in mechanism.links.items()}
    reach, travels = [], []
    for joint in mechanism.joints:
        if isinstance(joint, Revolute):
            for link, point in zip(joint.links, joint.points):
                local.setdefault(link, []).append(point)
            reach.append(joint_point(joint, motion)[0][rows])
        else:
            local.setdefault(joint.slider, []).append(joint.slider_point)
            reach.append(motion.point(joint.slider, joint.slider_point)[rows])
            s = travel(joint, motion)[0][rows]
            travels.append((joint, float(np.nanmin(s)), float(np.nanmax(s))))
    reach += [motion.point(link, point)[rows] for _, link, point in mechanism.named_points]
    every = np.concatenate(reach)
    size = float(np.hypot(*(np.nanmax(every, axis=0) - np.nanmin(every, axis=0)))) or 1.0
    length = min(BLOCK[0] * size, SHORT * _shortest(local, size))
    guides = []
    for joint, low, high in travels:
        direction = np.array([np.cos(joint.guide_angle), np.sin(joint.guide_angle)])
        guides.append((joint, tuple(tuple(np.add(joint.guide_point, s * direction))
                                    for s in (low - length, high + length))))
    outlines = {}
    for link in mechanism.moving_links:
        nodes = _unique(local.get(link, []))
        # the guides it carries lengthen a bar along them (a slotted crank or lever) and
        # make a link that is little more than a guide; they do not widen a plate
        longer = _unique(list(nodes) + [end for joint, ends in guides
                                        if joint.carrier == link for end in ends])
        if len(nodes) < 2 or (len(longer) >= 2 and len(_hull(longer)) == 2):
            nodes = longer
        if len(nodes) >= 2:
            outlines[link] = nodes[_hull(nodes)]
    return _Layout(outlines, guides, (length, length * BLOCK[1] / BLOCK[0]), size)


def _shortest(local: dict, size: float) -> float:
    """[m] the shortest distance between two distinct points of one link (``size`` when
    no link has two)."""
    shortest = size
    for points in local.values():
        nodes = _unique(points)
        if len(nodes) > 1:
            gaps = np.hypot(*(nodes[:, None] - nodes[None]).transpose(2, 0, 1))
            shortest = min(shortest, float(gaps[gaps > 1e-9].min()))
    return shortest


def _place(lay: _Layout, result) -> Geometry:
    """The layout at a result's reported positions (limits left to the caller)."""
    mechanism, motion, rows = result.mechanism, result.kinematics.motion, result.rows
    bodies = [Body(link, np.stack([motion.point(link, tuple(p)) for p in outline], axis=1)[rows])
              for link, outline in lay.outlines.items()]
    sliders = [_slider(joint, motion, rows, ends, *lay.block) for joint, ends in lay.guides]
    pins, pivots = {}, {}
    for joint in mechanism.joints:
        if isinstance(joint, Revolute):
            pins[joint.name] = joint_point(joint, motion)[0][rows]
            if FRAME in joint.links:
                pivots[joint.name] = np.asarray(joint.points[joint.links.index(FRAME)], float)
    points = {name: motion.point(link, point)[rows] for name, link, point in mechanism.named_points}
    return Geometry(result.crank_angle[rows], bodies, sliders, pins, pivots, points, points,
                    lay.size, (0.0, 0.0, 0.0, 0.0))


def geometry(result, positions=None) -> Geometry:
    """World coordinates of every drawn element at every reported position of
    ``positions`` (default: of ``result``), laid out and scaled from the sweep of
    ``result``, whose named points' paths it carries.

    >>> import dyade
    >>> from dyade.plot.mechanism import geometry
    >>> g = geometry(dyade.analyse(dyade.read_mechanism("mechanisms/slider-crank.toml")))
    >>> [(body.link, body.outline.shape) for body in g.bodies]
    [(2, (361, 2, 2)), (3, (361, 2, 2))]
    >>> [slider.joint for slider in g.sliders]
    [(1, 4)]
    """
    lay = _layout(result)
    swept = _place(lay, result)
    drawn = [np.concatenate(list(swept.pins.values()))]
    drawn += [b.outline.reshape(-1, 2) for b in swept.bodies]
    drawn += [part.reshape(-1, 2) for s in swept.sliders for part in (s.rails, s.block)]
    drawn += [p[None] - [0.0, 1.5 * PIVOT * lay.size] for p in swept.pivots.values()]
    corner = np.concatenate(drawn)
    low, high = np.nanmin(corner, axis=0), np.nanmax(corner, axis=0)
    margin = 0.04 * lay.size
    swept.limits = (float(low[0] - margin), float(high[0] + margin), float(low[1] - margin),
                    float(high[1] + margin))
    if positions is None:
        return swept
    placed = _place(lay, positions)
    placed.paths, placed.limits = swept.points, swept.limits
    return placed


def _slider(joint: Prismatic, motion, rows, ends, length: float, height: float) -> Slider:
    """The block around the slider point and the two rails along the guide."""
    d = motion.direction(joint.carrier, joint.guide_angle)[rows]
    n = perp(d)
    centre = motion.point(joint.slider, joint.slider_point)[rows]
    block = np.stack([centre + sa * 0.5 * length * d + sb * 0.5 * height * n
                      for sa, sb in ((-1, -1), (1, -1), (1, 1), (-1, 1))], axis=1)
    on_guide = np.stack([motion.point(joint.carrier, end)[rows] for end in ends], axis=1)
    rails = np.stack([on_guide + side * 0.5 * height * n[:, None] for side in (-1.0, 1.0)],
                     axis=1)
    return Slider(joint.name, joint.carrier, joint.carrier == FRAME, block, rails)


class Scene:
    """The linkage's artists on one axes, moved to a position by ``update(k)``."""

    def __init__(self, ax, geo: Geometry, paths: bool = True) -> None:
        from matplotlib.patches import Polygon

        self.geo = geo
        size = geo.size
        for name, path in geo.paths.items() if paths else ():
            ax.plot(path[:, 0], path[:, 1], color=canvas.GREY, linewidth=0.8,
                    linestyle=canvas.DASHES[2], zorder=1, gid=f"path-{name}")
        for name, at in geo.pivots.items():
            _ground(ax, at, PIVOT * size, f"pivot-{name[0]}-{name[1]}")
        self.bodies = []
        for body in geo.bodies:
            colour = link_colour(body.link)
            on_top = 3.0 + 0.5 / body.link  # the crank over the links it drives
            if body.plate:
                artist = ax.add_patch(Polygon(body.outline[0], closed=True, facecolor=colour,
                                              alpha=0.25, edgecolor=colour, linewidth=1.4,
                                              zorder=on_top - 0.5, gid=f"link-{body.link}"))
            else:
                artist, = ax.plot(*body.outline[0].T, color=colour, linewidth=3.2,
                                  solid_capstyle="round", zorder=on_top, gid=f"link-{body.link}")
            label = ax.annotate(str(body.link), _anchor(body, 0), xytext=(0.0, 0.0),
                                textcoords="offset points", fontsize=LINK_SIZE, ha="center",
                                va="center", zorder=8, color="0.1", gid=f"link-label-{body.link}",
                                bbox={"boxstyle": "circle,pad=0.15", "facecolor": "white",
                                      "edgecolor": colour, "linewidth": 0.6},
                                arrowprops={"arrowstyle": "-", "color": colour,
                                            "linewidth": 0.5, "shrinkA": 0, "shrinkB": 0})
            self.bodies.append((body, artist, label))
        self.sliders = []
        for slider in geo.sliders:
            a, b = slider.joint
            rails, = ax.plot(*_rails(slider.rails[0]).T, linewidth=1.0, zorder=2,
                             color="0.15" if slider.fixed_guide else link_colour(slider.carrier),
                             gid=f"guide-{a}-{b}")
            if slider.fixed_guide:
                _hatched_rails(ax, slider.rails[0], PIVOT * size * 0.4)
            block = ax.add_patch(Polygon(slider.block[0], closed=True,  # pins show through
                                         facecolor=(1.0, 1.0, 1.0, 0.55),
                                         edgecolor="black", linewidth=1.1, zorder=4,
                                         gid=f"block-{a}-{b}"))
            self.sliders.append((slider, rails, block))
        self.pins, = ax.plot(*np.stack(list(geo.pins.values()), axis=0)[:, 0].T,
                             linestyle="none", marker="o", markersize=4.5,
                             markerfacecolor="white", markeredgecolor="black",
                             markeredgewidth=1.0, zorder=6, gid="pins")
        self.ax, self.points, self.point_labels = ax, None, []
        if geo.points:
            self.points, = ax.plot(*np.stack(list(geo.points.values()))[:, 0].T,
                                   linestyle="none", marker="s", markersize=3.5, color="black",
                                   zorder=7, gid="points")
            self.point_labels = [ax.annotate(name, path[0], xytext=(4, 4),
                                             textcoords="offset points", fontsize=POINT_SIZE,
                                             ha="center", va="center", zorder=8,
                                             gid=f"point-label-{name}",
                                             arrowprops={"arrowstyle": "-", "color": "0.45",
                                                         "linewidth": 0.5, "shrinkA": 0,
                                                         "shrinkB": 1})
                                 for name, path in geo.points.items()]
        ax.set_xlim(*geo.limits[:2])
        ax.set_ylim(*geo.limits[2:])
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")

    def update(self, k: int) -> list:
        """Put every moving artist at reported position k; returns them."""
        moved = []
        for body, artist, label in self.bodies:
            if body.plate:
                artist.set_xy(body.outline[k])
            else:
                artist.set_data(*body.outline[k].T)
            label.xy = _anchor(body, k)
            moved += [artist, label]
        for slider, rails, block in self.sliders:
            if not slider.fixed_guide:
                rails.set_data(*_rails(slider.rails[k]).T)
            block.set_xy(slider.block[k])
            moved += [rails, block]
        self.pins.set_data(*np.stack(list(self.geo.pins.values()))[:, k].T)
        moved.append(self.pins)
        if self.points is not None:
            self.points.set_data(*np.stack(list(self.geo.points.values()))[:, k].T)
            for text, path in zip(self.point_labels, self.geo.points.values()):
                text.xy = path[k]
            moved += [self.points, *self.point_labels]
        return moved

    def place(self, k: int) -> None:
        """Put the link numbers and point names of position k where they are clear of
        each other and of the drawing (the axes in their final place on the figure)."""
        places = Placer(self.ax)
        for body, _, _ in self.bodies:
            outline = body.outline[k]
            places.avoid(np.concatenate([outline, outline[:1]]) if body.plate else outline)
        for slider, _, _ in self.sliders:
            places.avoid(np.concatenate([slider.block[k], slider.block[k][:1]]))
            places.avoid(_rails(slider.rails[k]))
        places.avoid(np.stack(list(self.geo.pins.values()))[:, k])
        points = list(self.geo.points.values())
        if points:
            places.avoid(np.stack(points)[:, k])
        centre = np.nanmean(np.stack(list(self.geo.pins.values()))[:, k], axis=0)
        for text, path in zip(self.point_labels, points):  # the names first: they are points
            text.xyann = places.place(path[k], text.get_text(), POINT_SIZE,
                                      first=_away(places, path[k], centre))
            text.arrow_patch.set_visible(leader(text.xyann) is not None)
        for body, _, label in self.bodies:
            label.xyann = places.place(label.xy, label.get_text(), LINK_SIZE, pad=2.5,
                                       first=_away(places, label.xy, centre))
            label.arrow_patch.set_visible(leader(label.xyann) is not None)


def _anchor(body: Body, k: int) -> np.ndarray:
    """Where a link's number points: the middle of a bar, the centre of a plate."""
    return body.outline[k].mean(axis=0)


def _away(places: Placer, at: np.ndarray, centre: np.ndarray) -> float:
    """[rad] the direction from the drawing's centre to ``at`` on the screen."""
    d = places.display(at)[0] - places.display(centre)[0]
    return float(np.arctan2(d[1], d[0])) if np.isfinite(d).all() else 0.0


def link_colour(link: int) -> str:
    return canvas.COLOURS[(link - 2) % len(canvas.COLOURS)]


def _rails(rails: np.ndarray) -> np.ndarray:
    """Two segments (2, 2, 2) as one polyline with a break between them."""
    return np.concatenate([rails[0], [[np.nan, np.nan]], rails[1]])


def _hatched_rails(ax, rails: np.ndarray, depth: float) -> None:
    """The frame side of a fixed guide: a hatched strip outside each rail."""
    from matplotlib.patches import Polygon

    for k, rail in enumerate(rails):
        outward = rail.mean(axis=0) - rails[1 - k].mean(axis=0)
        outward = outward / (np.hypot(*outward) or 1.0) * depth
        strip = np.concatenate([rail, rail[::-1] + outward])
        ax.add_patch(Polygon(strip, closed=True, facecolor="none", edgecolor=canvas.GREY,
                             hatch="////", linewidth=0.0, zorder=1, gid="frame-guide"))


def _ground(ax, at: np.ndarray, height: float, gid: str) -> None:
    """A frame pivot: a triangle under the pin on a hatched base."""
    from matplotlib.patches import Polygon, Rectangle

    x, y = at
    ax.add_patch(Polygon([(x, y), (x - 0.6 * height, y - height), (x + 0.6 * height, y - height)],
                         closed=True, facecolor="white", edgecolor="black", linewidth=0.9,
                         zorder=2, gid=gid))
    ax.add_patch(Rectangle((x - height, y - 1.5 * height), 2 * height, 0.5 * height,
                           facecolor="none", edgecolor=canvas.GREY, hatch="////",
                           linewidth=0.0, zorder=2))
    ax.plot([x - height, x + height], [y - height, y - height], color="black", linewidth=0.9,
            zorder=2)


def figure(result, *, at_deg=None, fig: Figure | None = None, **renamed) -> Figure:
    """The linkage at crank angles ``at_deg`` [°], one panel each, over the paths of its
    named points traced over the sweep of ``result``.

    Parameters
    ----------
    result : Result
        A sweep (``dyade.analyse``): the paths and the common scale of the panels.
    at_deg : iterable of float, optional
        Crank angles [°] (default: four positions spread over a full turn, else the
        sweep's start, middle and end).
    fig : Figure, optional
        A figure to draw on (default: a new one).
    **renamed
        The former ``at`` [rad] is refused with an ``InputError`` naming ``at_deg``.

    Raises
    ------
    AssemblyError
        The linkage cannot close at one of the angles ``at_deg``.

    Examples
    --------
    >>> import dyade
    >>> from dyade.plot import mechanism
    >>> result = dyade.analyse(dyade.read_mechanism("mechanisms/fourbar.toml"))
    >>> [ax.get_title() for ax in mechanism.figure(result, at_deg=[0, 90]).axes]
    ['φ21 = 0°', 'φ21 = 90°']
    """
    from dyade.errors import InputError
    from dyade.linkage.options import angles_in_degrees
    from dyade.linkage.plan import Plan
    from dyade.linkage.sweep import analyse_si

    InputError.refuse_renamed("mechanism.figure", renamed, {"at": "at_deg"})
    at = angles_in_degrees(at_deg, "at_deg")
    if at is None:
        angle = result.crank_angle[result.rows]
        span = angle[-1] - angle[0]
        full = span >= 2 * np.pi - 1.5 * result.mechanism.sweep.step
        if result.rows.all():
            at = angle[0] + span * (np.arange(4) / 4 if full else np.arange(3) / 2)
        else:  # a sweep with gaps (allow_partial): positions where it closes, spread
            k = np.linspace(0, angle.size - 1, 5)[:4] if full else np.linspace(0, angle.size - 1, 3)
            at = angle[np.unique(np.round(k).astype(int))]
    at = np.atleast_1d(np.asarray(at, dtype=float))
    placed = geometry(result, analyse_si(result.mechanism, crank_angle=at, plan=Plan()))
    cams = None
    if result.mechanism.cam is not None:  # the cam that drives link 2, at each angle
        cams = cam_outlines(result.mechanism.cam, at)
        low, high = np.nanmin(cams[0].reshape(-1, 2), 0), np.nanmax(cams[0].reshape(-1, 2), 0)
        x0, x1, y0, y1 = placed.limits
        margin = 0.04 * placed.size
        placed.limits = (min(x0, low[0] - margin), max(x1, high[0] + margin),
                         min(y0, low[1] - margin), max(y1, high[1] + margin))
    width = panel_width(placed)
    rows, columns = canvas.grid(len(at), 1 if width > 1.5 * PANEL else 3 if len(at) == 3 else 2)
    with canvas.style():
        fig = canvas.new(width * columns, (panel_height(placed) + 0.5) * rows + 0.3, fig)
        axes = fig.subplots(rows, columns, squeeze=False).ravel()
        for ax in axes[len(at):]:
            ax.set_visible(False)
        scenes = []
        for k, ax in enumerate(axes[:len(at)]):
            scenes.append(Scene(ax, placed))
            scenes[-1].update(k)
            if cams is not None:
                draw_cam(ax, result.mechanism.cam, cams[0][k], cams[1][k])
            ax.set_title(f"{'θ' if cams is not None else 'φ21'} = {np.rad2deg(at[k]):.4g}°")
        fig.suptitle(result.mechanism.name)
        fig.draw_without_rendering()  # the panels' final place: labels are placed in it
        for k, scene in enumerate(scenes):
            scene.place(k)
        fig.set_layout_engine("none")  # keep the places the labels were fitted to
    return fig


CAM_POINTS = 720  # points of a cam's drawn outline over the turn


def cam_outlines(drive, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The cam's working curve [m] in the mechanism's frame at the cam angles ``theta``
    [rad], shape (angles, ``CAM_POINTS``, 2), and the roller centre there, (angles, 2)
    (``dyade.model.cam.CamDrive``: the cam's frame turned by θ, by −θ for a clockwise
    cam, then by β about its centre)."""
    from dyade.cam.follower import curves, follower_motion

    cam = drive.cam
    turn = np.linspace(0.0, 2.0 * np.pi, CAM_POINTS)
    working = curves(cam, turn)[0].working  # (the cam's own frame)
    sense = -1.0 if cam.clockwise else 1.0
    angle = sense * np.asarray(theta, dtype=float)[:, None] + drive.angle
    c, s = np.cos(angle)[..., None], np.sin(angle)[..., None]
    x, y = working[None, :, 0:1], working[None, :, 1:2]
    outline = np.concatenate((c * x - s * y, s * x + c * y), axis=-1) + np.asarray(drive.centre)
    motion = follower_motion(drive, np.asarray(theta, dtype=float))
    roller = motion.contact + cam.roller_radius * motion.normal
    return outline, roller


def draw_cam(ax, drive, outline: np.ndarray, roller: np.ndarray) -> None:
    """The cam (its working curve, filled), its centre and the roller on link 2."""
    from matplotlib.patches import Circle, Polygon

    ax.add_patch(Polygon(outline, closed=True, facecolor="0.9", edgecolor="black",
                         linewidth=1.2, zorder=2.5, gid="cam"))  # over the guide
    ax.plot(*drive.centre, marker="+", color="black", markersize=8, zorder=6,
            gid="cam-centre")
    if drive.cam.roller_radius:
        ax.add_patch(Circle(tuple(roller), drive.cam.roller_radius, facecolor="white",
                            edgecolor="black", linewidth=1.0, zorder=4.5, gid="roller"))


def panel_width(geo: Geometry) -> float:
    """[in] a panel's width: ``PANEL``, wider for a linkage with many labels (up to
    ``WIDEST`` times)."""
    count = len(geo.bodies) + len(geo.points)
    return PANEL * float(np.clip(np.sqrt(count / CROWD), 1.0, WIDEST))


def panel_height(geo: Geometry) -> float:
    """[in] a panel's height for the drawing's aspect at ``panel_width`` wide."""
    x0, x1, y0, y1 = geo.limits
    return panel_width(geo) * float(np.clip((y1 - y0) / (x1 - x0), 0.45, 1.6))
