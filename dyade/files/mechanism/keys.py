"""The top-level keys of a mechanism file, below every part's reader: the profile
reader (``dyade.files.profile``) accepts them in a mechanism file's [profile], and the
mechanism reader reads a [servo]'s profile with it."""

from __future__ import annotations

TOP_KEYS = {"name", "description", "units", "sweep", "frame", "crank", "dyad", "links",
            "gravity", "load", "spring", "friction", "drive", "drive_line", "servo", "profile",
            "cam", "follower", "manufacture"}
