"""Reports: result -> named columns (SI, angles in degrees) -> CSV, JSON, rich tables."""
