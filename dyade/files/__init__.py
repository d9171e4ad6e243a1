"""Reading input files: a shared schema of typed, unit-checked keys and one reader per file kind."""
