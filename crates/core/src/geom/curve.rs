//! The closed set of curve families splinescope draws, behind one enum.

use glam::DVec3;

use super::family::{AtTau, Family};
use super::{Aabb, BezierSegment, GeomError, Lower, ParamCurve};

/// The one table of curve families: one row per family, `Variant(Type) = "name"`, with
/// the variant's documentation (its formula's paper). Every list of families is generated
/// from it: [`Curve`] here, the `From` conversions, [`Curve::FAMILY_NAMES`]; in the
/// presentation layer each family's report (`FamilyDetails`) and the templates; in the
/// scene layer the written forms
/// (`FamilyDoc`) and the codecs' reader table. Where a list cannot be generated it is an
/// exhaustive `match` ([`each_family!`](crate::each_family)), so a new row does not compile
/// until every place has the new family. `name` must equal the type's [`Family::NAME`]
/// (checked at compile time).
///
/// Call it with the name of a macro taking the rows
/// (`$( $(#[$doc:meta])* $variant:ident($ty:ty) = $name:literal ),*`).
#[macro_export]
macro_rules! family_table {
    ($then:ident) => {
        $then! {
            /// A Bézier curve of any degree (all papers).
            Bezier($crate::geom::Bezier) = "bezier",
            /// `R(t) = Q(t) + S(t) v` (paper 002, §4).
            ModifiedBezier($crate::geom::ModifiedBezier) = "modified_bezier",
            /// Cubic Bézier interpolation, plain or modified (paper 002, §5).
            Interpolation($crate::geom::CubicInterpolation) = "interpolation",
            /// A non-uniform B-spline of any order (paper 001, §2).
            BSpline($crate::geom::BSpline) = "bspline",
            /// A B-spline with multiple shape parameters (paper 001, §3–5).
            Nubmp($crate::geom::Nubmp) = "nubmp",
            /// A rational Bézier curve, `Σ w_i P_i B_i / Σ w_i B_i` (conics exact).
            RationalBezier($crate::geom::RationalBezier) = "rational_bezier",
            /// A NURBS curve, `Σ w_i P_i N_{i,k} / Σ w_i N_{i,k}`.
            Nurbs($crate::geom::Nurbs) = "nurbs",
            /// Bézier segments of any degree (each may be rational) joined end to end.
            Path($crate::geom::Path) = "path",
        }
    };
}

/// Whether two names are equal, at compile time.
#[doc(hidden)]
#[must_use]
pub const fn same_name(a: &str, b: &str) -> bool {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

macro_rules! define_families {
    ($( $(#[$doc:meta])* $variant:ident($ty:ty) = $name:literal ),* $(,)?) => {
        /// Every curve family splinescope knows, generated from
        /// [`family_table!`](crate::family_table). Each one implements [`Family`] in its
        /// own file: it evaluates exactly in `f64` ([`ParamCurve`]), lowers exactly to
        /// Bézier segments ([`Lower`]) and describes its overlays and structure edits;
        /// what it says to a person (controls, summaries, reports) is in the
        /// presentation layer above core.
        #[derive(Debug, Clone, PartialEq)]
        pub enum Curve {
            $( $(#[$doc])* $variant($ty), )*
        }

        $(
            impl From<$ty> for Curve {
                fn from(c: $ty) -> Curve {
                    Curve::$variant(c)
                }
            }

            const _: () = assert!(
                same_name(<$ty as Family>::NAME, $name),
                concat!("the family table's name ", $name, " differs from the type's Family::NAME")
            );
        )*

        impl Curve {
            /// Every family's name ([`Family::NAME`]), in the table's order: what scene
            /// files write in `type`, and the order error messages list them in.
            pub const FAMILY_NAMES: &'static [&'static str] = &[$($name),*];

            /// A curve of family `family` (a name of [`Curve::FAMILY_NAMES`]) for generated
            /// scenes: [`Family::generated`]; `None` for a name not in the table.
            ///
            /// # Errors
            /// The family's error when the points break it.
            pub fn generated(
                family: &str,
                degree: usize,
                point: &mut dyn FnMut() -> DVec3,
            ) -> Option<Result<Curve, GeomError>> {
                match family {
                    $( $name => Some(<$ty as Family>::generated(degree, point).map(Curve::from)), )*
                    _ => None,
                }
            }

        }
    };
}

family_table!(define_families);

/// Calls `$body` with `$c` bound to the family inside a [`Curve`] (for the layers above,
/// which dispatch one generic call over every family the same way).
#[doc(hidden)]
#[macro_export]
macro_rules! each_family {
    ($curve:expr, $c:ident => $body:expr) => {
        match $curve {
            $crate::geom::Curve::Bezier($c) => $body,
            $crate::geom::Curve::ModifiedBezier($c) => $body,
            $crate::geom::Curve::Interpolation($c) => $body,
            $crate::geom::Curve::BSpline($c) => $body,
            $crate::geom::Curve::Nubmp($c) => $body,
            $crate::geom::Curve::RationalBezier($c) => $body,
            $crate::geom::Curve::Nurbs($c) => $body,
            $crate::geom::Curve::Path($c) => $body,
        }
    };
}

impl Curve {
    /// Checks the values derived from the input: every control point of the lowering
    /// (interpolation tangents and inner points, B-spline extraction, NUBMP dual points)
    /// must be a finite number, or the curve is refused with what overflowed. Scenes run
    /// this on every curve they load and every edit they accept, so nothing downstream
    /// (evaluation, drawing, reports) meets a non-finite value.
    ///
    /// # Errors
    /// [`GeomError::DerivedNotFinite`] naming the segment and point.
    pub fn check_derived(&self) -> Result<(), GeomError> {
        // The input the overflow most likely comes from.
        let field = each_family!(self, c => c.derived_field());
        for (s, seg) in self.lower().iter().enumerate() {
            for (j, p) in seg.bezier.points().iter().enumerate() {
                if let Some(&value) = p.to_array().iter().find(|v| !v.is_finite()) {
                    return Err(GeomError::DerivedNotFinite {
                        field,
                        what: format!("control point {j} of lowered Bézier segment {s}"),
                        value,
                    });
                }
            }
            if !(seg.t0.is_finite() && seg.t1.is_finite()) {
                return Err(GeomError::DerivedNotFinite {
                    field,
                    what: format!("the parameter range of lowered Bézier segment {s}"),
                    value: if seg.t0.is_finite() { seg.t1 } else { seg.t0 },
                });
            }
        }
        Ok(())
    }

    /// The family's name as written in scene files (`"bezier"`, …): [`Family::NAME`].
    #[must_use]
    pub fn family(&self) -> &'static str {
        fn name<F: Family>(_: &F) -> &'static str {
            F::NAME
        }
        each_family!(self, c => name(c))
    }

    /// The variant's position in [`Curve::FAMILY_NAMES`].
    #[must_use]
    pub fn family_index(&self) -> usize {
        let name = self.family();
        Curve::FAMILY_NAMES
            .iter()
            .position(|n| *n == name)
            .unwrap_or_else(|| unreachable!("every family is in the table"))
    }

    /// The points the user places (drawn as dots): [`Family::control_points`].
    #[must_use]
    pub fn control_points(&self) -> &[DVec3] {
        each_family!(self, c => c.control_points())
    }

    /// The same curve with control point `index` (as listed by [`Curve::control_points`])
    /// moved to `p`; every other property (parameters, knots, shape parameters, `t*`, `v`)
    /// is kept.
    ///
    /// # Errors
    /// [`GeomError::NoSuchPoint`] for an index out of range, [`GeomError::NonFinitePoint`]
    /// for a non-finite `p`, or the family's own error when the moved point breaks it.
    pub fn with_control_point(&self, index: usize, p: DVec3) -> Result<Curve, GeomError> {
        let count = self.control_points().len();
        if index >= count {
            return Err(GeomError::NoSuchPoint { index, count });
        }
        let mut pts = self.control_points().to_vec();
        pts[index] = p;
        self.with_control_points(pts)
    }

    /// The same curve with every [`Curve::control_points`] replaced (same count); every
    /// other property is kept.
    ///
    /// # Errors
    /// [`GeomError::NonFinitePoint`] for a non-finite point, or the family's own error.
    pub fn with_control_points(&self, pts: Vec<DVec3>) -> Result<Curve, GeomError> {
        crate::geom::bezier::check_finite(&pts)?;
        each_family!(self, c => c.with_control_points(pts).map(Into::into))
    }

    /// A box holding the whole curve: [`Family::control_box`].
    #[must_use]
    pub fn control_box(&self) -> Aabb {
        each_family!(self, c => c.control_box())
    }

    /// Whether every point has `z = 0`.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        each_family!(self, c => c.is_planar())
    }

    /// What the structure allows at `τ`: [`Family::at_tau`].
    ///
    /// # Errors
    /// `τ` outside the domain, or a derived structure that overflows.
    pub fn at_tau(&self, tau: f64) -> Result<Option<AtTau>, GeomError> {
        each_family!(self, c => c.at_tau(tau))
    }

    /// Whether points are inserted by knot insertion: [`Family::inserts_by_knot`].
    #[must_use]
    pub fn inserts_by_knot(&self) -> bool {
        each_family!(self, c => c.inserts_by_knot())
    }

    /// The curve with a new control point `at` on its control polygon, and the point's
    /// index: [`Family::with_point_on_polygon`].
    ///
    /// # Errors
    /// [`GeomError::StructureRefused`] for families that insert by knot,
    /// [`GeomError::NonFinitePoint`] for a non-finite `at`, or the family's own error.
    pub fn with_point_on_polygon(&self, at: DVec3) -> Result<(Curve, usize), GeomError> {
        crate::geom::bezier::check_finite(&[at])?;
        each_family!(self, c => c.with_point_on_polygon(at).map(|(c, i)| (c.into(), i)))
    }

    /// The curve with the knot `t` inserted: [`Family::with_knot_inserted`].
    ///
    /// # Errors
    /// [`GeomError::StructureRefused`] for families that insert on the polygon, or the
    /// knot vector's error.
    pub fn with_knot_inserted(&self, t: f64) -> Result<Curve, GeomError> {
        each_family!(self, c => c.with_knot_inserted(t).map(Into::into))
    }

    /// The curve without control point `index`: [`Family::with_point_removed`].
    ///
    /// # Errors
    /// [`GeomError::NoSuchPoint`], [`GeomError::StructureRefused`] or the family's own
    /// error.
    pub fn with_point_removed(&self, index: usize) -> Result<Curve, GeomError> {
        let count = self.control_points().len();
        if index >= count {
            return Err(GeomError::NoSuchPoint { index, count });
        }
        each_family!(self, c => c.with_point_removed(index).map(Into::into))
    }
}

impl ParamCurve for Curve {
    fn domain(&self) -> (f64, f64) {
        each_family!(self, c => c.domain())
    }
    fn eval(&self, t: f64) -> DVec3 {
        each_family!(self, c => ParamCurve::eval(c, t))
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        each_family!(self, c => ParamCurve::eval_deriv(c, t))
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        each_family!(self, c => ParamCurve::eval_second_deriv(c, t))
    }
}

impl Lower for Curve {
    fn lower(&self) -> Vec<BezierSegment> {
        each_family!(self, c => c.lower())
    }
}
