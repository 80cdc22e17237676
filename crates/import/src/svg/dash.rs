//! SVG dashes: a `stroke-dasharray` and `stroke-dashoffset` read into a pattern in user
//! units, and a subpath cut into the open paths where the pattern is on — cut exactly
//! (de Casteljau on each segment, rational ones in homogeneous coordinates) at the
//! parameters where the arc length, measured in the element's user units as SVG
//! measures it, reaches each dash's ends.

use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{Path, PathSegment};

/// A dash pattern in user units: on and off lengths (an even count, not all 0, none
/// negative) and where along the pattern the path starts.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Dashes {
    lengths: Vec<f64>,
    offset: f64,
}

/// What a `stroke-dasharray` value says.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum DashArray {
    /// `none`, or a pattern that draws the stroke solid (every length 0; SVG draws a
    /// negative length as solid too).
    Solid,
    /// The lengths, in user units.
    Lengths(Vec<f64>),
    /// Lengths in units relative to a font or a viewport (`em`, `ex`, `%`): not read.
    Relative,
}

/// Reads a `stroke-dasharray` value (`none`, or lengths separated by commas or spaces, in
/// user units or absolute units at 96 per inch); `None` for one that does not parse
/// (ignored, as CSS ignores an invalid declaration).
pub(super) fn parse_dasharray(value: &str) -> Option<DashArray> {
    let value = value.trim();
    if value == "none" {
        return Some(DashArray::Solid);
    }
    let mut lengths = Vec::new();
    for item in value
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
    {
        let l: svgtypes::Length = item.parse().ok()?;
        let per = match l.unit {
            svgtypes::LengthUnit::None | svgtypes::LengthUnit::Px => 1.0,
            svgtypes::LengthUnit::In => 96.0,
            svgtypes::LengthUnit::Cm => 96.0 / 2.54,
            svgtypes::LengthUnit::Mm => 96.0 / 25.4,
            svgtypes::LengthUnit::Pt => 96.0 / 72.0,
            svgtypes::LengthUnit::Pc => 16.0,
            _ => return Some(DashArray::Relative),
        };
        let v = l.number * per;
        if !v.is_finite() {
            return None;
        }
        if v < 0.0 {
            return Some(DashArray::Solid);
        }
        lengths.push(v);
    }
    if lengths.is_empty() {
        return None;
    }
    if lengths.iter().all(|&l| l == 0.0) {
        return Some(DashArray::Solid);
    }
    Some(DashArray::Lengths(lengths))
}

impl Dashes {
    /// The pattern of `lengths` (an odd count repeated to make it even) started at
    /// `offset`.
    pub(super) fn new(lengths: &[f64], offset: f64) -> Dashes {
        let mut lengths = lengths.to_vec();
        if lengths.len() % 2 == 1 {
            lengths.extend_from_within(..);
        }
        Dashes { lengths, offset }
    }

    /// The dashes of `path` (in user units): the open paths where the pattern is on, in
    /// order; a dash of length 0 is left out. On a closed path whose pattern is on where
    /// it starts and where it ends, the last dash and the first are one, across the
    /// start. `Err(n)` when there would be more than `budget` dashes (`n` of them).
    pub(super) fn cut(&self, path: &Path, budget: u64) -> Result<Vec<Path>, String> {
        let analysis = CurveAnalysis::new(path);
        let end = path.segments().len() as f64;
        let polygon: f64 = path
            .segments()
            .iter()
            .flat_map(|s| s.points.windows(2).map(|w| (w[1] - w[0]).length()))
            .sum();
        let accuracy = (polygon * 1e-12).max(f64::MIN_POSITIVE);
        let total = analysis
            .length(0.0, end, accuracy)
            .map_err(|e| format!("its length: {e}"))?
            .value;
        let period: f64 = self.lengths.iter().sum();
        let dashes_per_period = (self.lengths.len() / 2) as f64;
        let count = ((total / period).ceil() + 1.0) * dashes_per_period;
        if count.is_nan() || count > budget as f64 {
            return Err(format!(
                "stroke-dasharray: about {count:.0} dashes on a path {total} long, more than the {budget} curves left under the limit"
            ));
        }
        // Where the pattern is at the path's start.
        let mut phase = self.offset.rem_euclid(period);
        let mut i = 0;
        while phase >= self.lengths[i] && phase > 0.0 {
            phase -= self.lengths[i];
            i = (i + 1) % self.lengths.len();
        }
        let mut left = self.lengths[i] - phase;
        let mut s = 0.0;
        let mut spans: Vec<(f64, f64)> = Vec::new();
        while s < total {
            let step = left.min(total - s);
            if i % 2 == 0 && step > 0.0 {
                spans.push((s, s + step));
            }
            s += step;
            i = (i + 1) % self.lengths.len();
            left = self.lengths[i];
        }
        let at = |s: f64| -> Result<f64, String> {
            if s <= 0.0 {
                return Ok(0.0);
            }
            if s >= total {
                return Ok(end);
            }
            analysis
                .parameter_at_length(s, accuracy)
                .map_err(|e| format!("a dash's end: {e}"))
        };
        let mut out = Vec::with_capacity(spans.len());
        for &(a, b) in &spans {
            let (ta, tb) = (at(a)?, at(b)?);
            if ta < tb {
                out.push(path.between(ta, tb).map_err(|e| e.to_string())?);
            }
        }
        // A closed path dashed across its start: the last dash goes on into the first.
        if path.is_closed()
            && out.len() >= 2
            && spans.first().is_some_and(|s| s.0 == 0.0)
            && spans.last().is_some_and(|s| s.1 >= total)
        {
            let first = out.remove(0);
            let last = out.pop().unwrap_or_else(|| unreachable!("two or more"));
            let joined: Vec<PathSegment> = last
                .segments()
                .iter()
                .chain(first.segments())
                .cloned()
                .collect();
            out.push(Path::try_new(joined, false).map_err(|e| e.to_string())?);
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn line(len: f64) -> Path {
        Path::try_new(
            vec![PathSegment::polynomial(vec![
                DVec3::ZERO,
                DVec3::new(len, 0.0, 0.0),
            ])],
            false,
        )
        .expect("a line")
    }

    #[test]
    fn patterns_parse_as_svg_reads_them() {
        assert_eq!(parse_dasharray("none"), Some(DashArray::Solid));
        assert_eq!(
            parse_dasharray("5, 3 2"),
            Some(DashArray::Lengths(vec![5.0, 3.0, 2.0]))
        );
        assert_eq!(parse_dasharray("1in"), Some(DashArray::Lengths(vec![96.0])));
        assert_eq!(parse_dasharray("0 0"), Some(DashArray::Solid));
        assert_eq!(parse_dasharray("4 -1"), Some(DashArray::Solid));
        assert_eq!(parse_dasharray("2em"), Some(DashArray::Relative));
        assert_eq!(parse_dasharray("5 x"), None);
    }

    #[test]
    fn a_line_is_cut_where_the_pattern_says_with_the_offset() {
        // 10 long, pattern 3 on 2 off (odd "3 2 1" would repeat): dashes [0,3], [5,8].
        let d = Dashes::new(&[3.0, 2.0], 0.0).cut(&line(10.0), 100).unwrap();
        let ends: Vec<(f64, f64)> = d
            .iter()
            .map(|p| {
                let s = p.segments();
                (s[0].points[0].x, s[s.len() - 1].points[1].x)
            })
            .collect();
        assert_eq!(ends, vec![(0.0, 3.0), (5.0, 8.0)]);
        // Offset 4: the pattern starts 1 into its gap: [1,4], [6,9].
        let d = Dashes::new(&[3.0, 2.0], 4.0).cut(&line(10.0), 100).unwrap();
        let x: Vec<f64> = d.iter().map(|p| p.segments()[0].points[0].x).collect();
        assert_eq!(x, vec![1.0, 6.0]);
        // An odd count repeats: "3 1 2" is 3 on 1 off 2 on 3 off 1 on 2 off.
        let d = Dashes::new(&[3.0, 1.0, 2.0], 0.0)
            .cut(&line(12.0), 100)
            .unwrap();
        assert_eq!(d.len(), 3);
        // Too many dashes for the budget: refused, saying how many.
        let e = Dashes::new(&[0.001, 0.001], 0.0)
            .cut(&line(10.0), 100)
            .unwrap_err();
        assert!(e.contains("dashes") && e.contains("100"), "{e}");
    }
}
