"""Motion laws (VDI 2143) and motion profiles over a machine cycle: the engine.

``dyade.motion.laws``: the laws as closed forms of the normalised time;
``dyade.motion.profile``: a profile of segments evaluated at any master angle or time.
"""
