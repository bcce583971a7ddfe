//! Pocket strategies: zigzag, contour-offset, adaptive spiral.
