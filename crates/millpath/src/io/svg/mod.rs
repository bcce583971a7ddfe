//! Pocket outlines from SVG drawings, at the size the drawing program meant.
//!
//! [`read_loops`] returns every closed outline in mm with what it read and skipped
//! ([`Drawing`]); [`parse`] hands them to the outer-outline/island classification.
//!
//! * **Size.** User units become mm through the root's `width`/`height` and `viewBox` (SVG
//!   2, §8.2): with both, the viewBox is fitted into the width × height (in mm: `px` and unit-
//!   less are 25.4/96 mm, `pt` 25.4/72, `pc` 25.4/6, `in`, `cm`, `mm`) per
//!   `preserveAspectRatio` (default `xMidYMid meet`); without a viewBox a user unit is a CSS
//!   pixel, 25.4/96 mm; without width/height the viewBox's units are pixels.
//!   [`ReadOptions::mm_per_unit`] overrides all of this with a fixed scale.
//! * **Placement.** SVG's y axis points down: the drawing is mirrored about the page's
//!   bottom edge (`y_mm = page height − y`), so it is the right way up and, for a page of
//!   known height, at the coordinates Inkscape's DXF export gives it. Arcs' bulges change sign
//!   with the mirror.
//! * **Transforms.** `transform` on any element (`matrix`, `translate`, `scale`, `rotate`,
//!   `skewX`, `skewY`, lists of them) composes down the tree (`crate::io::affine`; arcs
//!   stay exact under similarities).
//! * **Elements:** `path`, `rect` (with `rx`/`ry`), `circle`, `ellipse`, `line`, `polyline`,
//!   `polygon`, `use` (of any element with an id, `x`/`y` added; `symbol` content drawn only
//!   through `use`), nested `svg` (its `x`/`y`); `defs`, `clipPath`, `mask`, `marker`,
//!   `pattern` content is not drawn; `display="none"` elements are skipped; `text`, `image`
//!   and the rest are counted and skipped.
//! * **Depth.** Groups, nested `svg` and the rest may nest to any depth: the walk keeps its
//!   own stack rather than the thread's. A `use` reached through more than 16 other `use`
//!   references, or one inside its own target, is skipped with that reason (a cycle never
//!   ends otherwise); at most a million elements are drawn with every `use` expanded, so
//!   references that double at each level are refused rather than followed.
//! * **Joins:** open paths are chained end to end within [`ReadOptions::join_tolerance`]
//!   (`crate::io::join`).
//! * **Layers:** [`ReadOptions::layer`] keeps the outlines inside the `<g>` whose
//!   `inkscape:label` or `id` is that name.
//!
//! Why not `usvg`: it turns every arc into cubic Béziers (millpath keeps circles exact to
//! G2/G3), drops `inkscape:label`, and drops unpainted elements; the XML is read with
//! `roxmltree` (usvg's own XML parser) and the rest is the few hundred lines below.

mod path;

use super::affine::{Affine, Piece, transform_piece};
use super::drawing::{Drawing, ReadOptions};
use super::join::join;
use super::outline_json::Loops;
use crate::error::InputError;
use roxmltree::{Document, Node};
use std::collections::{HashMap, HashSet};

pub use path::MIN_TOLERANCE_MM;

const INKSCAPE_NS: &str = "http://www.inkscape.org/namespaces/inkscape";
const XLINK_NS: &str = "http://www.w3.org/1999/xlink";
const MAX_USE_DEPTH: usize = 16;
const MAX_ELEMENTS: usize = 1_000_000;

/// Millimetres per unit of an SVG length unit, `None` for relative units.
fn unit_mm(u: svgtypes::LengthUnit) -> Option<f64> {
    use svgtypes::LengthUnit as U;
    Some(match u {
        U::None | U::Px => 25.4 / 96.0,
        U::Mm => 1.0,
        U::Cm => 10.0,
        U::In => 25.4,
        U::Pt => 25.4 / 72.0,
        U::Pc => 25.4 / 6.0,
        _ => return None,
    })
}

/// A length as the file wrote it.
fn show(l: svgtypes::Length) -> String {
    use svgtypes::LengthUnit as U;
    let u = match l.unit {
        U::None => "",
        U::Px => "px",
        U::Mm => "mm",
        U::Cm => "cm",
        U::In => "in",
        U::Pt => "pt",
        U::Pc => "pc",
        _ => "?",
    };
    format!("{}{u}", l.number)
}

/// A length attribute in mm (`None` when absent, relative or unreadable).
fn length_mm(v: Option<&str>) -> Option<(f64, svgtypes::Length)> {
    let l: svgtypes::Length = v?.trim().parse().ok()?;
    Some((l.number * unit_mm(l.unit)?, l))
}

/// A coordinate attribute in user units (absolute units converted at 96 px per inch).
fn num(node: Node<'_, '_>, name: &str) -> f64 {
    let Some(v) = node.attribute(name) else {
        return 0.0;
    };
    match v.trim().parse::<svgtypes::Length>() {
        Ok(l) => match unit_mm(l.unit) {
            Some(mm) => l.number * mm / (25.4 / 96.0),
            None => l.number,
        },
        Err(_) => 0.0,
    }
}

/// The map from the root's user units to mm (y up) and its description.
fn root_map(root: Node<'_, '_>, opts: &ReadOptions) -> (Affine, String) {
    let vb = root
        .attribute("viewBox")
        .and_then(|v| v.parse::<svgtypes::ViewBox>().ok())
        .filter(|v| v.w > 0.0 && v.h > 0.0);
    let w = length_mm(root.attribute("width"));
    let h = length_mm(root.attribute("height"));
    let (map, text, page_h) = if let Some(s) = opts.mm_per_unit {
        (
            Affine::scale(s, s),
            format!("{s} mm per user unit (given)"),
            None,
        )
    } else {
        match (vb, w, h) {
            (Some(vb), Some((wm, wl)), Some((hm, hl))) => {
                let r = vb;
                let (sx, sy) = (wm / r.w, hm / r.h);
                let par = root
                    .attribute("preserveAspectRatio")
                    .and_then(|v| v.parse::<svgtypes::AspectRatio>().ok())
                    .unwrap_or_default();
                use svgtypes::Align as A;
                let (sx, sy) = match par.align {
                    A::None => (sx, sy),
                    _ if par.slice => (sx.max(sy), sx.max(sy)),
                    _ => (sx.min(sy), sx.min(sy)),
                };
                let (fx, fy) = match par.align {
                    A::None | A::XMinYMin => (0.0, 0.0),
                    A::XMidYMin => (0.5, 0.0),
                    A::XMaxYMin => (1.0, 0.0),
                    A::XMinYMid => (0.0, 0.5),
                    A::XMidYMid => (0.5, 0.5),
                    A::XMaxYMid => (1.0, 0.5),
                    A::XMinYMax => (0.0, 1.0),
                    A::XMidYMax => (0.5, 1.0),
                    A::XMaxYMax => (1.0, 1.0),
                };
                let tx = fx * (wm - r.w * sx) - r.x * sx;
                let ty = fy * (hm - r.h * sy) - r.y * sy;
                (
                    Affine([sx, 0.0, 0.0, sy, tx, ty]),
                    format!(
                        "mm: width {}, height {}, viewBox {} {} {} {} ({:.6} mm per user unit)",
                        show(wl),
                        show(hl),
                        r.x,
                        r.y,
                        r.w,
                        r.h,
                        sx
                    ),
                    Some(hm),
                )
            }
            (Some(vb), _, _) => {
                let px = 25.4 / 96.0;
                let r = vb;
                (
                    Affine([px, 0.0, 0.0, px, -r.x * px, -r.y * px]),
                    "px (viewBox without width/height: 1 user unit = 1 px = 25.4/96 mm)".to_owned(),
                    Some(r.h * px),
                )
            }
            (None, _, h) => {
                let px = 25.4 / 96.0;
                (
                    Affine::scale(px, px),
                    "px (no viewBox: 1 user unit = 1 px = 25.4/96 mm)".to_owned(),
                    h.map(|h| h.0),
                )
            }
        }
    };
    let flip = Affine([1.0, 0.0, 0.0, -1.0, 0.0, page_h.unwrap_or(0.0)]);
    (flip.after(map), text)
}

struct Walker<'a, 'input> {
    opts: &'a ReadOptions,
    origin: &'a str,
    ids: HashMap<&'a str, Node<'a, 'input>>,
    /// Ids a `textPath` follows: construction geometry for the text, not outlines.
    text_guides: HashSet<&'a str>,
    drawing: Drawing,
    pieces: Vec<Piece>,
    visited: usize,
}

fn layer_names<'a>(n: Node<'a, '_>) -> impl Iterator<Item = &'a str> {
    n.attribute((INKSCAPE_NS, "label"))
        .into_iter()
        .chain(n.attribute("id"))
}

/// One element still to be drawn: the element, the transform and layer state its ancestors
/// (or the `use` that reached it) give it, and how many `use` references led to it.
#[derive(Clone, Copy)]
struct Pending<'a, 'input> {
    node: Node<'a, 'input>,
    ctm: Affine,
    on_layer: bool,
    /// A nested `svg` (not the root) places its content at its `x`/`y`.
    nested: bool,
    use_depth: usize,
}

impl<'a, 'input> Walker<'a, 'input> {
    /// Draws `root` and everything under it, depth first in document order. The walk keeps
    /// its own stack instead of recursing, so that no nesting depth can exhaust the thread's.
    fn walk(&mut self, root: Node<'a, 'input>, ctm: Affine) -> Result<(), InputError> {
        let mut stack = vec![Pending {
            node: root,
            ctm,
            on_layer: false,
            nested: false,
            use_depth: 0,
        }];
        while let Some(p) = stack.pop() {
            self.visit(p, &mut stack)?;
        }
        Ok(())
    }

    /// Draws one element; the elements it contains (or refers to) go on `stack`, last first.
    fn visit(
        &mut self,
        p: Pending<'a, 'input>,
        stack: &mut Vec<Pending<'a, 'input>>,
    ) -> Result<(), InputError> {
        let Pending {
            node: n,
            ctm,
            on_layer,
            nested,
            use_depth,
        } = p;
        self.visited += 1;
        if self.visited > MAX_ELEMENTS {
            return Err(
                InputError::new("SVG elements", format!("more than {MAX_ELEMENTS}"))
                    .at(self.origin)
                    .expected("a drawing of at most a million elements (with `use` expanded)"),
            );
        }
        let name = n.tag_name().name();
        if n.attribute("display").is_some_and(|d| d.trim() == "none")
            || n.attribute("style")
                .is_some_and(|s| s.replace(' ', "").contains("display:none"))
        {
            self.drawing.skip(name, "hidden (display: none)");
            return Ok(());
        }
        if n.attribute("id")
            .is_some_and(|id| self.text_guides.contains(id))
        {
            self.drawing
                .skip(name, "the path a text follows (textPath)");
            return Ok(());
        }
        let mut ctm = ctm;
        if let Some(t) = n.attribute("transform") {
            let tf: svgtypes::Transform = t.parse().map_err(|e| {
                InputError::new("SVG transform", t)
                    .at(self.at(n))
                    .expected(format!("an SVG transform list ({e})"))
            })?;
            let a = Affine([tf.a, tf.b, tf.c, tf.d, tf.e, tf.f]);
            if !a.is_valid() {
                self.drawing.skip(name, "singular transform");
                return Ok(());
            }
            ctm = ctm.after(a);
        }
        let mut on_layer = on_layer;
        if name == "g" {
            let names: Vec<&str> = layer_names(n).collect();
            for l in &names {
                self.drawing.layers.insert((*l).to_owned());
            }
            if let Some(want) = &self.opts.layer
                && names.iter().any(|l| l == want)
            {
                on_layer = true;
            }
        }
        let d = match name {
            "svg" | "g" | "a" | "switch" => {
                let mut ctm = ctm;
                if name == "svg" && nested {
                    ctm = ctm.after(Affine::translate(num(n, "x"), num(n, "y")));
                }
                push_children(stack, n, ctm, on_layer, use_depth);
                return Ok(());
            }
            "use" => {
                let href = n
                    .attribute((XLINK_NS, "href"))
                    .or_else(|| n.attribute("href"))
                    .unwrap_or("");
                let target = href
                    .strip_prefix('#')
                    .and_then(|id| self.ids.get(id))
                    .copied();
                let Some(target) = target else {
                    self.drawing.skip("use", "its target is missing");
                    return Ok(());
                };
                if n.ancestors().any(|a| a == target) {
                    self.drawing.skip("use", "refers to itself");
                    return Ok(());
                }
                if use_depth >= MAX_USE_DEPTH {
                    self.drawing.skip(
                        "use",
                        &format!("more than {MAX_USE_DEPTH} `use` references deep (a cycle?)"),
                    );
                    return Ok(());
                }
                self.drawing.count("use");
                let ctm = ctm.after(Affine::translate(num(n, "x"), num(n, "y")));
                if target.tag_name().name() == "symbol" {
                    push_children(stack, target, ctm, on_layer, use_depth + 1);
                } else {
                    stack.push(Pending {
                        node: target,
                        ctm,
                        on_layer,
                        nested: true,
                        use_depth: use_depth + 1,
                    });
                }
                return Ok(());
            }
            "path" => n.attribute("d").unwrap_or("").to_owned(),
            "rect" => {
                let (x, y, w, h) = (num(n, "x"), num(n, "y"), num(n, "width"), num(n, "height"));
                if !(w > 0.0 && h > 0.0) {
                    self.drawing.skip(name, "zero width or height");
                    return Ok(());
                }
                let (rx, ry) = match (n.attribute("rx"), n.attribute("ry")) {
                    (None, None) => (0.0, 0.0),
                    (Some(_), None) => (num(n, "rx"), num(n, "rx")),
                    (None, Some(_)) => (num(n, "ry"), num(n, "ry")),
                    _ => (num(n, "rx"), num(n, "ry")),
                };
                let (rx, ry) = (rx.clamp(0.0, w / 2.0), ry.clamp(0.0, h / 2.0));
                if rx > 0.0 && ry > 0.0 {
                    format!(
                        "M {} {y} H {} A {rx} {ry} 0 0 1 {} {} V {} A {rx} {ry} 0 0 1 {} {} \
                         H {} A {rx} {ry} 0 0 1 {x} {} V {} A {rx} {ry} 0 0 1 {} {y} Z",
                        x + rx,
                        x + w - rx,
                        x + w,
                        y + ry,
                        y + h - ry,
                        x + w - rx,
                        y + h,
                        x + rx,
                        y + h - ry,
                        y + ry,
                        x + rx
                    )
                } else {
                    format!("M {x} {y} H {} V {} H {x} Z", x + w, y + h)
                }
            }
            "circle" | "ellipse" => {
                let (cx, cy) = (num(n, "cx"), num(n, "cy"));
                let (rx, ry) = if name == "circle" {
                    (num(n, "r"), num(n, "r"))
                } else {
                    (num(n, "rx"), num(n, "ry"))
                };
                if !(rx > 0.0 && ry > 0.0) {
                    self.drawing.skip(name, "zero radius");
                    return Ok(());
                }
                format!(
                    "M {} {cy} A {rx} {ry} 0 0 1 {} {cy} A {rx} {ry} 0 0 1 {} {cy} Z",
                    cx - rx,
                    cx + rx,
                    cx - rx
                )
            }
            "line" => format!(
                "M {} {} L {} {}",
                num(n, "x1"),
                num(n, "y1"),
                num(n, "x2"),
                num(n, "y2")
            ),
            "polyline" | "polygon" => {
                let pts = n.attribute("points").unwrap_or("");
                let close = if name == "polygon" { " Z" } else { "" };
                format!("M {pts}{close}")
            }
            "defs" | "symbol" | "clipPath" | "mask" | "marker" | "pattern" | "metadata"
            | "title" | "desc" | "style" | "script" | "namedview" | "linearGradient"
            | "radialGradient" | "filter" => return Ok(()),
            "text" => {
                self.drawing.skip(name, "text");
                return Ok(());
            }
            _ => {
                self.drawing.skip(name, "not an outline element");
                return Ok(());
            }
        };
        if self.opts.layer.is_some() && !on_layer {
            self.drawing.skip(name, "on another layer");
            return Ok(());
        }
        let at = self.at(n);
        let local_tol = self.opts.tolerance / ctm.max_stretch();
        let tol = local_tol.max(MIN_TOLERANCE_MM);
        for p in path::subpaths(&d, tol, &at)? {
            self.pieces
                .push(transform_piece(p, &ctm, self.opts.tolerance));
        }
        self.drawing.count(name);
        Ok(())
    }

    fn at(&self, n: Node<'_, '_>) -> String {
        let pos = n.document().text_pos_at(n.range().start);
        match n.attribute("id") {
            Some(id) => format!(
                "{}, line {} <{} id={id:?}>",
                self.origin,
                pos.row,
                n.tag_name().name()
            ),
            None => format!(
                "{}, line {} <{}>",
                self.origin,
                pos.row,
                n.tag_name().name()
            ),
        }
    }
}

/// Puts the element children of `n` on `stack` so that the first is taken first.
fn push_children<'a, 'input>(
    stack: &mut Vec<Pending<'a, 'input>>,
    n: Node<'a, 'input>,
    ctm: Affine,
    on_layer: bool,
    use_depth: usize,
) {
    let first = stack.len();
    stack.extend(n.children().filter(Node::is_element).map(|c| Pending {
        node: c,
        ctm,
        on_layer,
        nested: true,
        use_depth,
    }));
    stack[first..].reverse();
}

/// Reads the closed outlines of an SVG document, in mm; `origin` names the file.
pub fn read_loops(text: &str, origin: &str, opts: &ReadOptions) -> Result<Drawing, InputError> {
    opts.validate(origin)?;
    let doc = Document::parse_with_options(
        text,
        roxmltree::ParsingOptions {
            allow_dtd: true,
            nodes_limit: 4_000_000,
            ..roxmltree::ParsingOptions::default()
        },
    )
    .map_err(|e| {
        InputError::new("SVG", e.to_string())
            .at(origin)
            .expected("a well-formed SVG (XML) document")
    })?;
    let root = doc.root_element();
    let (map, units) = root_map(root, opts);
    if !map.is_valid() {
        return Err(InputError::new("SVG size", units)
            .at(origin)
            .expected("a finite, non-zero width, height and viewBox"));
    }
    let ids = doc
        .descendants()
        .filter_map(|n| n.attribute("id").map(|id| (id, n)))
        .collect();
    let text_guides = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "textPath")
        .filter_map(|n| {
            n.attribute((XLINK_NS, "href"))
                .or_else(|| n.attribute("href"))
        })
        .filter_map(|h| h.strip_prefix('#'))
        .collect();
    let mut w = Walker {
        opts,
        origin,
        ids,
        text_guides,
        drawing: Drawing {
            units,
            mm_per_unit: map.max_stretch(),
            layer: opts.layer.clone(),
            ..Drawing::default()
        },
        pieces: Vec::new(),
        visited: 0,
    };
    // The root's own transform attribute is not part of SVG 1.1 but SVG 2 allows it.
    w.walk(root, map)?;
    let mut drawing = w.drawing;
    if let Some(want) = &opts.layer
        && !drawing.layers.contains(want)
    {
        return Err(InputError::new("layer", want).at(origin).expected(format!(
            "the inkscape:label or id of a <g>: {}",
            drawing
                .layers
                .iter()
                .cloned()
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let joined = join(w.pieces, opts.join_tolerance);
    drawing.open = joined.open;
    drawing.degenerate = joined.degenerate;
    drawing.add_closed(&joined.closed, origin, opts.tolerance);
    Ok(drawing)
}

/// Reads the loops of an SVG document; `tolerance` bounds the flattening of curves, mm.
pub fn parse(text: &str, origin: &str, tolerance: f64) -> Result<Loops, InputError> {
    if !(tolerance.is_finite() && tolerance >= MIN_TOLERANCE_MM) {
        return Err(InputError::new("SVG flattening tolerance", tolerance)
            .at(origin)
            .expected(format!("a finite number ≥ {MIN_TOLERANCE_MM} mm")));
    }
    let opts = ReadOptions {
        tolerance,
        ..ReadOptions::default()
    };
    parse_with(text, origin, &opts)
}

/// [`parse`] with every option.
pub fn parse_with(text: &str, origin: &str, opts: &ReadOptions) -> Result<Loops, InputError> {
    read_loops(text, origin, opts)?.into_loops(origin, opts.join_tolerance)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Page in mm with a viewBox of the same size: 1 mm per user unit, y = 100 − y.
    fn mm_page(body: &str) -> String {
        format!(r#"<svg width="100mm" height="100mm" viewBox="0 0 100 100">{body}</svg>"#)
    }

    #[test]
    fn rounded_square_keeps_exact_arcs_and_islands() {
        let svg = mm_page(
            r#"<path d="M 0 0 H 10 A 5 5 0 0 1 10 10 H 0 Z"/><circle cx="4" cy="5" r="1"/>"#,
        );
        let l = parse(&svg, "t.svg", 0.001).unwrap();
        let area = 100.0 + std::f64::consts::PI * 12.5;
        assert!(
            (l.outer.signed_area() - area).abs() < 1e-9,
            "{}",
            l.outer.signed_area()
        );
        assert_eq!(l.islands.len(), 1);
        // Exact arcs: 2 vertices for the circle, 4 for the rounded square.
        assert_eq!((l.outer.len(), l.islands[0].len()), (4, 2));
    }

    /// The `outline_importers` fuzzer's abort (7.5 GB): an elliptical half turn of radius
    /// 1e55 mm. Refused by its radius and sweep before kurbo subdivides it; a legitimate
    /// elliptical arc, and a nearly straight one of a huge ellipse, still read.
    #[test]
    fn huge_elliptical_arcs_are_refused_before_subdivision() {
        let e = parse(
            &mm_page(r#"<path d="M 0 0 A 1e55 1e11 10 1 1 1000 0 Z"/>"#),
            "huge.svg",
            1e-6,
        )
        .unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.contains("SVG arc") && msg.contains("1e55") && msg.contains("huge.svg"),
            "{msg}"
        );
        let ok = parse(
            &mm_page(r#"<path d="M 0 0 A 20 10 0 0 0 40 0 L 40 -10 L 0 -10 Z"/>"#),
            "ellipse.svg",
            0.001,
        )
        .unwrap();
        assert!(ok.outer.signed_area().abs() > 400.0);
        let flat = parse(
            &mm_page(r#"<path d="M 0 0 A 1e9 5e8 0 0 1 10 0 L 10 -10 L 0 -10 Z"/>"#),
            "flat.svg",
            0.001,
        )
        .unwrap();
        assert!((flat.outer.signed_area().abs() - 100.0).abs() < 1e-3);
    }

    /// A mirror in a transform (scale(1, −1)) flips arcs: the rounded square's area is kept.
    #[test]
    fn mirroring_transforms_keep_arcs_exact() {
        let svg = mm_page(
            r#"<g transform="translate(0 50) scale(1 -1)"><path d="M 0 0 H 10 A 5 5 0 0 1 10 10 H 0 Z"/></g>"#,
        );
        let l = parse(&svg, "m.svg", 0.001).unwrap();
        let area = 100.0 + std::f64::consts::PI * 12.5;
        assert!((l.outer.signed_area() - area).abs() < 1e-9);
        let b = l.outer.bounds();
        assert!(
            (b.max.x - 15.0).abs() < 1e-9 && (b.min.y - 50.0).abs() < 1e-9,
            "{b:?}"
        );
    }
}
