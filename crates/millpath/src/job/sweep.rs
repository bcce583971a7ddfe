//! The transition sweep behind `millpath sweep` and the demo's Figure 10: the cycle time of
//! the spiral against zigzag over transition ratios C and feeds (the adaptive-spiral paper's
//! Table 1 and Figure 10), every toolpath timed by the look-ahead planner on the machine.
//!
//! The transition C belongs to the paper's central spiral, which the `fronts` and `harmonic`
//! morphs draw; the default (`offsets`) morph has none, so a sweep on it runs `fronts`.

use crate::Error;
use crate::machine::Machine;
use crate::report::plots;
use crate::strategy::pocket::{self, PocketOptions, PocketShape, SpiralMorph, StrategyKind};
use crate::toolpath::Tool;
use serde::Serialize;

/// The result of a sweep: zigzag's time per feed and the spiral's per (C, feed).
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    /// Machine whose planner timed every toolpath.
    pub machine: String,
    /// Transition ratios C.
    pub ratios: Vec<f64>,
    /// Feeds, in/min.
    pub feeds_ipm: Vec<f64>,
    /// Zigzag cycle time per feed, s.
    pub zigzag_s: Vec<f64>,
    /// Spiral cycle time, `spiral_s[c][f]` for `ratios[c]` and `feeds_ipm[f]`, s.
    pub spiral_s: Vec<Vec<f64>>,
    /// How the times were computed.
    pub cycle_time_model: String,
}

impl Sweep {
    /// Gain of the spiral over zigzag in %, positive when the spiral is faster.
    pub fn gain(&self, c: usize, f: usize) -> f64 {
        match (
            self.spiral_s.get(c).and_then(|r| r.get(f)),
            self.zigzag_s.get(f),
        ) {
            (Some(t), Some(z)) if *z > 0.0 => 100.0 * (z - t) / z,
            _ => f64::NAN,
        }
    }

    /// The paper's Figure 10: one curve per feed, zigzag dashed in the same colour.
    pub fn chart(&self) -> plots::Chart {
        let curves: Vec<(String, Vec<(f64, f64)>)> = self
            .feeds_ipm
            .iter()
            .enumerate()
            .map(|(f, feed)| {
                (
                    format!("{feed:.0} in/min"),
                    self.ratios
                        .iter()
                        .enumerate()
                        .filter_map(|(c, r)| Some((*r, *self.spiral_s.get(c)?.get(f)?)))
                        .collect(),
                )
            })
            .collect();
        let refs: Vec<(String, f64)> = self
            .feeds_ipm
            .iter()
            .zip(&self.zigzag_s)
            .map(|(_, t)| (String::new(), *t))
            .collect();
        let mut chart = plots::cycle_time_vs_transition_with(&curves, &refs);
        chart.title = format!(
            "Cycle time against C on {}: spiral solid, zigzag dashed",
            self.machine
        );
        chart
    }
}

/// Times zigzag at every feed and the spiral at every (C, feed) on `machine`; `base` gives
/// everything else. `progress` is called after each toolpath with (done, total).
pub fn sweep(
    shape: &PocketShape,
    tool: &Tool,
    base: &PocketOptions,
    machine: &Machine,
    ratios: &[f64],
    feeds_ipm: &[f64],
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Sweep, Error> {
    let total = feeds_ipm.len() * (1 + ratios.len());
    let mut done = 0;
    // The transition C is the paper's central spiral's, which the fronts and harmonic morphs
    // draw; the default (offsets) morph has none.
    let morph = match base.spiral.morph {
        SpiralMorph::Offsets => SpiralMorph::Fronts,
        m => m,
    };
    let mut time = |kind: StrategyKind, feed: f64, c: f64| -> Result<f64, Error> {
        let o = base
            .clone()
            .with_feed(feed * 25.4 / 60.0)
            .with_transition(c)
            .with_morph(morph);
        let tp = pocket::toolpath(kind, shape, tool, &o)?;
        let t = crate::motion::cycle_time(&tp, machine)
            .map_err(|e| e.engine_made("timing the pocket toolpath"))?;
        done += 1;
        progress(done, total);
        Ok(t)
    };
    let zigzag_s = feeds_ipm
        .iter()
        .map(|f| time(StrategyKind::Zigzag, *f, base.spiral.transition))
        .collect::<Result<Vec<_>, _>>()?;
    let spiral_s = ratios
        .iter()
        .map(|c| {
            feeds_ipm
                .iter()
                .map(|f| time(StrategyKind::Spiral, *f, *c))
                .collect::<Result<Vec<_>, _>>()
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Sweep {
        machine: machine.name.clone(),
        ratios: ratios.to_vec(),
        feeds_ipm: feeds_ipm.to_vec(),
        zigzag_s,
        spiral_s,
        cycle_time_model: crate::motion::CYCLE_TIME_MODEL.to_owned(),
    })
}

impl Sweep {
    /// The table as CSV: `feed_ipm,strategy,C,cycle_time_s,gain_pct`, zigzag rows first.
    pub fn csv(&self) -> String {
        let mut rows = vec!["feed_ipm,strategy,C,cycle_time_s,gain_pct".to_owned()];
        for (f, t) in self.feeds_ipm.iter().zip(&self.zigzag_s) {
            rows.push(format!("{f},zigzag,,{t:.3},"));
        }
        for (c, ratio) in self.ratios.iter().enumerate() {
            for (f, feed) in self.feeds_ipm.iter().enumerate() {
                let t = self.spiral_s[c][f];
                rows.push(format!(
                    "{feed},spiral,{ratio},{t:.3},{:.2}",
                    self.gain(c, f)
                ));
            }
        }
        rows.join("\n") + "\n"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Outline, Point};

    /// A 60 × 40 mm pocket, one level of 3 mm, a 6 mm tool.
    fn setup() -> (PocketShape, Tool, PocketOptions) {
        let pts =
            [(0.0, 0.0), (60.0, 0.0), (60.0, 40.0), (0.0, 40.0)].map(|(x, y)| Point::new(x, y));
        let outer = Outline::from_points(&pts, "rect").unwrap();
        let shape = PocketShape::new(outer, Vec::new(), "rect").unwrap();
        let opts = PocketOptions::default().with_depth(3.0).with_step_down(3.0);
        (shape, Tool::flat(6.0).unwrap(), opts)
    }

    #[test]
    fn every_toolpath_is_timed_and_faster_feeds_are_not_slower() {
        let (shape, tool, base) = setup();
        let m = Machine::preset("hsm").unwrap();
        let mut calls = Vec::new();
        let t = sweep(
            &shape,
            &tool,
            &base,
            &m,
            &[0.3, 0.6],
            &[100.0, 400.0],
            &mut |d, n| {
                calls.push((d, n));
            },
        )
        .unwrap();
        assert_eq!(calls, [(1, 6), (2, 6), (3, 6), (4, 6), (5, 6), (6, 6)]);
        assert_eq!(t.zigzag_s.len(), 2);
        assert_eq!((t.spiral_s.len(), t.spiral_s[0].len()), (2, 2));
        // Each zigzag time is at least its cut at the programmed feed: the shape's area
        // swept once by a 6 mm tool is over (60·40 − slack)/6 mm long at 100 in/min.
        let lower = (60.0 - 6.0) * (40.0 - 6.0) / 6.0 / (100.0 * 25.4 / 60.0);
        assert!(t.zigzag_s[0] > lower, "{} vs {lower}", t.zigzag_s[0]);
        assert!(t.zigzag_s[1] < t.zigzag_s[0]);
        for row in &t.spiral_s {
            assert!(row[1] < row[0], "{row:?}");
        }
        // The gain and the CSV are the table's own figures.
        let g = t.gain(1, 0);
        assert!((g - 100.0 * (t.zigzag_s[0] - t.spiral_s[1][0]) / t.zigzag_s[0]).abs() < 1e-12);
        let csv = t.csv();
        assert_eq!(csv.lines().count(), 1 + 2 + 4);
        assert!(
            csv.contains(&format!("100,spiral,0.6,{:.3},{g:.2}", t.spiral_s[1][0])),
            "{csv}"
        );
        assert_eq!(t.chart().series.len(), 2 + 2);
    }
}
