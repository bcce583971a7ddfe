//! Biarcs within a tolerance (placeholder, filled below).
