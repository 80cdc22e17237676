//! Deterministic generators of stress scenes (many random curves), for benchmarks, the
//! viewer's stress mode and tests.

use glam::DVec3;

use splinescope_encoding::Color;

use super::{DEFAULT_SAMPLES_PER_SEGMENT, Scene, SceneCurve, Style, ViewSpec};
use splinescope_core::geom::Curve;

use splinescope_core::rng;

/// Options of [`random_bezier_scene`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StressOptions {
    /// How many curves.
    pub curves: usize,
    /// Their degree.
    pub degree: usize,
    /// Samples per segment.
    pub samples: u32,
    /// 3D control points instead of planar.
    pub three_d: bool,
    /// The generator's seed.
    pub seed: u64,
    /// The family of the curves.
    pub family: StressFamily,
}

/// The family of generated curves: a name of the core's family table
/// ([`Curve::FAMILY_NAMES`]), each family's curves made by its
/// [`splinescope_core::geom::Family::generated`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StressFamily(&'static str);

impl Default for StressFamily {
    /// Bézier curves.
    fn default() -> Self {
        StressFamily(Curve::FAMILY_NAMES[0])
    }
}

/// A family name that is not in the family table.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown curve family {name:?} (expected one of {})", Curve::FAMILY_NAMES.join(", "))]
pub struct UnknownFamily {
    /// The name given.
    pub name: String,
}

impl std::str::FromStr for StressFamily {
    type Err = UnknownFamily;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Curve::FAMILY_NAMES
            .iter()
            .find(|n| **n == s)
            .map(|n| StressFamily(n))
            .ok_or_else(|| UnknownFamily { name: s.to_owned() })
    }
}

impl StressFamily {
    /// Every family, in the table's order.
    pub fn all() -> impl Iterator<Item = StressFamily> {
        Curve::FAMILY_NAMES.iter().map(|n| StressFamily(n))
    }

    /// The family's name in scene files and on the command line.
    #[must_use]
    pub fn name(self) -> &'static str {
        self.0
    }

    /// One curve of `degree`, its points drawn from `point`.
    fn curve(self, degree: usize, point: &mut dyn FnMut() -> DVec3) -> Curve {
        match Curve::generated(self.0, degree, point) {
            Some(Ok(c)) => c,
            Some(Err(e)) => unreachable!("finite points in the unit cube make a valid curve: {e}"),
            None => unreachable!("the name comes from the family table"),
        }
    }

    /// A curve of `degree` on fixed points, for its structure.
    fn sample(self, degree: usize) -> Curve {
        let mut rng = rng::Rng::new(0);
        self.curve(degree, &mut || DVec3::new(rng.unit(), rng.unit(), 0.0))
    }

    /// Bézier segments one curve of `degree` lowers to.
    #[must_use]
    pub fn segments(self, degree: usize) -> usize {
        splinescope_core::geom::Lower::lower(&self.sample(degree)).len()
    }

    /// The highest degree of those segments for curves of `degree` (a NUBMP curve lowers
    /// through its dual, one degree higher).
    #[must_use]
    pub fn segment_degree(self, degree: usize) -> usize {
        splinescope_core::geom::max_degree(&splinescope_core::geom::Lower::lower(
            &self.sample(degree),
        ))
    }

    /// Control points of one curve of `degree`.
    #[must_use]
    pub fn points(self, degree: usize) -> usize {
        self.sample(degree).control_points().len()
    }
}

impl Default for StressOptions {
    fn default() -> Self {
        StressOptions {
            curves: 10_000,
            degree: 3,
            samples: DEFAULT_SAMPLES_PER_SEGMENT,
            three_d: false,
            seed: 1,
            family: StressFamily::default(),
        }
    }
}

/// Random Bézier curves of one degree, each wandering in a unit cell of a square grid,
/// drawn thin without overlays (the viewer's stress mode and the throughput benchmark).
#[must_use]
pub fn random_bezier_scene(opts: StressOptions) -> Scene {
    let mut rng = rng::Rng::new(opts.seed);
    let side = (opts.curves as f64).sqrt().ceil().max(1.0) as usize;
    let curves = (0..opts.curves)
        .map(|i| {
            let origin = DVec3::new((i % side) as f64, (i / side) as f64, 0.0);
            let curve = opts.family.curve(opts.degree, &mut || {
                let z = if opts.three_d {
                    rng.range(0.0, 1.0)
                } else {
                    0.0
                };
                origin + DVec3::new(rng.range(0.0, 1.0), rng.range(0.0, 1.0), z)
            });
            let hue = rng.unit() as f32;
            SceneCurve {
                name: None,
                curve,
                style: Style {
                    // On the 8-bit grid scene files write, so that a generated scene
                    // survives a save (or a pickle) unchanged.
                    color: Color::from_rgba8(
                        Color([0.2 + 0.6 * hue, 0.3, 0.8 - 0.6 * hue, 1.0]).to_rgba8(),
                    ),
                    width: 1.0,
                    width_in_scene: false,
                    show_polygon: false,
                    show_points: false,
                    samples: None,
                    stroke: Default::default(),
                },
            }
        })
        .collect();
    Scene {
        name: Some(format!(
            "{} random curves of degree {}",
            opts.curves, opts.degree
        )),
        unit: None,
        background: Color::WHITE,
        samples_per_segment: Some(opts.samples),
        view: ViewSpec::Auto,
        curves,
        annotations: Vec::new(),
    }
}

/// Deprecated: `splinescope_core::rng::Rng`.
#[deprecated(note = "use splinescope_core::rng::Rng")]
pub type Rng = rng::Rng;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_seed_same_scene_and_points_in_their_cell() {
        let opts = StressOptions {
            curves: 50,
            degree: 4,
            ..StressOptions::default()
        };
        let a = random_bezier_scene(opts);
        assert_eq!(a, random_bezier_scene(opts));
        for (i, c) in a.curves.iter().enumerate() {
            assert_eq!(c.curve.control_points().len(), 5);
            let cell = DVec3::new((i % 8) as f64, (i / 8) as f64, 0.0);
            for p in c.curve.control_points() {
                let d = *p - cell;
                assert!(
                    (0.0..1.0).contains(&d.x) && (0.0..1.0).contains(&d.y),
                    "{p}"
                );
            }
        }
    }
}
