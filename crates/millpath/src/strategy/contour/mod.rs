//! Contour strategy: cutter offset of a free-form outline, roughing layers and a finishing pass.
