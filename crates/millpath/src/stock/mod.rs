//! Material-removal simulation: engagement, gouge and coverage checks.
