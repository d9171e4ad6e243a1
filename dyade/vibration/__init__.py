"""Vibration of drive elements: the stiff coupling (Strümpfel), gear drives next."""
