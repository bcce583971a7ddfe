//! Reports: serde structs, SVG previews, plots, HTML.
