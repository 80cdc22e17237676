//! The classification of a cubic Bézier control polygon of paper 000, §2.3 (Fig. 2): the
//! three polygon types and the region of targets reachable while the end points and end
//! tangent directions are kept. The solver's region queries (containment, boundary) are in
//! [`crate::solve::shape`]; `docs/math.md` §2 records the decisions.

use glam::DVec3;

/// The three kinds of cubic control polygon of paper 000, §2.3 (Fig. 2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PolygonType {
    /// Type 1: the legs `P_0P_1` and `P_3P_2` are parallel.
    Parallel,
    /// Type 2: the legs' lines meet at `apex` ahead of both legs (`apex = P_0 + s e_1 =
    /// P_3 + r e_2`, `s, r > 0`).
    Converging {
        /// The intersection `X`.
        apex: DVec3,
    },
    /// Type 3: the lines meet behind a leg, or (in 3D) do not meet.
    Diverging,
}

impl PolygonType {
    /// The paper's number: 1, 2 or 3.
    #[must_use]
    pub fn number(&self) -> u8 {
        match self {
            PolygonType::Parallel => 1,
            PolygonType::Converging { .. } => 2,
            PolygonType::Diverging => 3,
        }
    }
}

/// The targets a cubic can reach while keeping its end points and end tangent directions
/// (paper 000, §2.3): `P′_1 = P_0 + s e_1`, `P′_2 = P_3 + r e_2` with `s, r ≥ 0` (the
/// tangents keep their direction). The reachable set is the open segment `P_0P_3` plus the
/// cone of `e_1, e_2`: every point `P_0 + λ(P_3 − P_0) + a e_1 + b e_2`, `λ ∈ (0, 1)`,
/// `a, b ≥ 0` — a strip or half-strip for type 1, a sector for types 2 and 3. For type 2
/// with the slides limited to `[P_0, X]` and `[P_3, X]` the region is the area between the
/// segment `P_0P_3` and the cubic `(P_0, X, X, P_3)`.
#[derive(Debug, Clone, PartialEq)]
pub struct CubicRegion {
    /// The polygon's type.
    pub kind: PolygonType,
    /// `P_0`.
    pub p0: DVec3,
    /// `P_3`.
    pub p3: DVec3,
    /// `e_1 = unit(P_1 − P_0)`.
    pub e1: DVec3,
    /// `e_2 = unit(P_2 − P_3)`.
    pub e2: DVec3,
}

impl CubicRegion {
    /// The finer classification `inspect` reports, and where the legs' lines meet:
    /// type 1 `"parallel"` (legs pointing the same way) or `"antiparallel"`; type 2
    /// `"converging"` (meeting at `X` ahead of both legs); type 3 `"diverging"` (meeting
    /// behind both legs), `"mixed"` (ahead of one, behind the other) or, in space,
    /// `"skew"` (the lines do not meet, no point).
    #[must_use]
    pub fn subtype(&self) -> (&'static str, Option<DVec3>) {
        match self.kind {
            PolygonType::Parallel => {
                if self.e1.dot(self.e2) > 0.0 {
                    ("parallel", None)
                } else {
                    ("antiparallel", None)
                }
            }
            PolygonType::Converging { apex } => ("converging", Some(apex)),
            PolygonType::Diverging => {
                let (s, r, x1, x2) = closest_line_points(self.p0, self.e1, self.p3, self.e2);
                let scale = (self.p3 - self.p0).length().max(1.0);
                if (x1 - x2).length() > REGION_TOLERANCE * scale.max(x1.length()) {
                    ("skew", None)
                } else if s < 0.0 && r < 0.0 {
                    ("diverging", Some(0.5 * (x1 + x2)))
                } else {
                    ("mixed", Some(0.5 * (x1 + x2)))
                }
            }
        }
    }
}

/// The closest points `p0 + s e1` and `p3 + r e2` of two non-parallel lines with unit
/// directions: `(s, r, x1, x2)`.
fn closest_line_points(p0: DVec3, e1: DVec3, p3: DVec3, e2: DVec3) -> (f64, f64, DVec3, DVec3) {
    let w = p0 - p3;
    let b = e1.dot(e2);
    let (d, e) = (e1.dot(w), e2.dot(w));
    let den = 1.0 - b * b;
    let s = (b * e - d) / den;
    let r = (e - b * d) / den;
    (s, r, p0 + s * e1, p3 + r * e2)
}

/// Relative tolerance of the region's geometric tests.
pub(crate) const REGION_TOLERANCE: f64 = 1e-9;

impl CubicRegion {
    /// Classifies the cubic control polygon `p` with unit end directions
    /// `[e_1, e_2]` (`e_1 = unit(P_1 − P_0)`, `e_2 = unit(P_2 − P_3)`).
    #[must_use]
    pub fn from_cubic(p: &[DVec3], [e1, e2]: [DVec3; 2]) -> CubicRegion {
        let (p0, p3) = (p[0], p[3]);
        let scale = (p3 - p0)
            .length()
            .max(p[1].length())
            .max(p[2].length())
            .max(1.0);
        let cross = e1.cross(e2);
        let kind = if cross.length() <= REGION_TOLERANCE {
            PolygonType::Parallel
        } else {
            // Closest points of the two lines: P0 + s e1 and P3 + r e2.
            let (s, r, x1, x2) = closest_line_points(p0, e1, p3, e2);
            if (x1 - x2).length() <= REGION_TOLERANCE * scale && s > 0.0 && r > 0.0 {
                PolygonType::Converging {
                    apex: 0.5 * (x1 + x2),
                }
            } else {
                PolygonType::Diverging
            }
        };
        CubicRegion {
            kind,
            p0,
            p3,
            e1,
            e2,
        }
    }
}
