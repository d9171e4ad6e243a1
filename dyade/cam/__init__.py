"""Disc cams and their followers (issue 40): the engine.

``geometry``: the pitch and working curves in closed form from the follower's motion
s(θ), s′(θ), s″(θ), the pressure angle, the radii of curvature, undercut, the smallest
base circle, for a translating roller follower (with offset), an oscillating roller
follower and a flat-faced translating follower. ``forces``: the contact force along the
common normal, the lift-off speed, the Hertz stress. ``export``: the points of a curve
at a chord tolerance (the profile to manufacture).

Conventions (docs/guide/cams.md): the cam turns counter-clockwise (θ grows
counter-clockwise) about the origin O of the frame; the follower moves along +y away
from O (a translating follower's line of motion is x = e, the offset); the cam frame is
the frame turned by θ, so a curve of the cam is the roller's (or the face's) path seen
from the cam. A cam turning clockwise is the mirror image (x -> -x): the same numbers
with e -> -e. SI throughout: lengths [m], angles [rad], s′ = ds/dθ [m/rad].
"""
