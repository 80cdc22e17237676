//! STEP in (`.step`, `.stp`; AP203, AP214, AP242): the curves of a Part 21 file as 3D
//! curves in the file's length unit.
//!
//! The syntax is parsed with `winnow` ([`part21`]); no Part 21 crate maps the curve
//! entities this needs (`truck-stepio` has no ellipse, trimmed or composite curves and no
//! units, and prints its errors). Mapped, exactly:
//! - `B_SPLINE_CURVE_WITH_KNOTS` and its rational complex form (with
//!   `RATIONAL_B_SPLINE_CURVE`): a B-spline or NURBS curve with the file's knots
//!   (multiplicities expanded), weights and control points — its own parameters;
//! - `BEZIER_CURVE`: the piecewise Bézier curve it is (knots at the integers);
//! - `LINE`, `CIRCLE`, `ELLIPSE` (placed by `AXIS2_PLACEMENT_3D`): conics as exact
//!   rational quadratics of at most 90° each;
//! - `TRIMMED_CURVE` (by parameter or by point; sense honoured; across a closed curve's
//!   seam), `COMPOSITE_CURVE` (its segments end to end, each in its sense), and the edges
//!   of a B-rep: `EDGE_CURVE` trimmed at its vertices (through `SURFACE_CURVE` and
//!   `SEAM_CURVE` to their 3D curve).
//!
//! Which curves a scene gets: every `EDGE_CURVE`, and every mapped curve no other entity
//! uses (a basis trimmed elsewhere, an edge's geometry, a surface's curve or a pcurve's 2D
//! curve is not drawn twice). The length unit (`SI_UNIT` with its prefix, or a
//! `CONVERSION_BASED_UNIT` such as the inch) is the scene's unit; a plane angle unit in
//! degrees scales conic parameters. Errors name the entity (`#id`, its type and line).

pub mod part21;

use std::collections::{BTreeMap, HashMap, HashSet};

use glam::{DVec2, DVec3};
use splinescope_core::geom::{BSpline, Curve, Lower, Nurbs, ParamCurve, Path, PathSegment};
use splinescope_io::limits;
use splinescope_scene::format::{SceneCurve, Style};

use crate::{ImportError, Imported};
use part21::{Instance, Record, Value};

/// Reads a STEP file's `text` as a scene.
///
/// # Errors
/// [`ImportError::Syntax`] where the file breaks Part 21's syntax, [`ImportError::Entity`]
/// for an entity whose parameters or references are wrong (naming its `#id`, type and
/// line), [`ImportError::Limit`] past a documented limit.
pub fn read(text: &str, file: &str) -> Result<Imported, ImportError> {
    let limit = |l: limits::Limit| {
        l.value().map_err(|source| ImportError::Limit {
            file: file.to_owned(),
            source,
        })
    };
    let bounds = part21::Bounds {
        instances: limit(limits::IMPORT_ELEMENTS)?,
        depth: limit(limits::IMPORT_DEPTH)?,
    };
    let lines = LineIndex::new(text);
    let instances = part21::parse(text, bounds).map_err(|e| {
        let (line, column) = lines.at(e.offset);
        ImportError::Syntax {
            file: file.to_owned(),
            line,
            column,
            message: e.message,
        }
    })?;
    let mut m = Model {
        file,
        lines: &lines,
        instances: &instances,
        max_points: limit(limits::POINTS)?,
        max_order: limit(limits::ORDER)?,
        max_depth: limit(limits::IMPORT_DEPTH)?,
        angle: 1.0,
        resolving: Vec::new(),
    };
    let unit = m.units()?;
    // Who uses each instance: a curve used by anything but a set or a representation is
    // part of something else.
    let mut used: HashSet<u64> = HashSet::new();
    for inst in instances.values() {
        let containers = inst.records.iter().all(|r| {
            matches!(
                r.name.as_str(),
                "GEOMETRIC_CURVE_SET"
                    | "GEOMETRIC_SET"
                    | "SHAPE_REPRESENTATION"
                    | "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION"
                    | "EDGE_BASED_WIREFRAME_SHAPE_REPRESENTATION"
                    | "STYLED_ITEM"
                    | "OVER_RIDING_STYLED_ITEM"
                    | "PRESENTATION_LAYER_ASSIGNMENT"
                    | "MECHANICAL_DESIGN_GEOMETRIC_PRESENTATION_REPRESENTATION"
                    | "REPRESENTATION"
            )
        });
        if containers {
            continue;
        }
        for r in &inst.records {
            refs(&r.params, &mut used);
        }
    }
    let mut ids: Vec<u64> = instances.keys().copied().collect();
    ids.sort_unstable();
    let mut curves = Vec::new();
    let mut left_out: BTreeMap<String, u64> = BTreeMap::new();
    for id in ids {
        let inst = &instances[&id];
        let name = inst.records[0].name.as_str();
        let edge = name == "EDGE_CURVE";
        let curve_kind = is_curve(inst);
        if !(edge || (curve_kind && !used.contains(&id))) {
            continue;
        }
        let pieces = if edge { m.edge(id)? } else { m.whole(id)? };
        let Some(pieces) = pieces else {
            *left_out
                .entry(format!("unbounded {}", name.to_lowercase()))
                .or_default() += 1;
            continue;
        };
        for (k, p) in pieces.into_iter().enumerate() {
            if let Err(source) = limits::CURVES.check(curves.len() as u64 + 1) {
                return Err(ImportError::Limit {
                    file: file.to_owned(),
                    source,
                });
            }
            let label = label_of(inst, id);
            let index = curves.len();
            let mut style = Style::default_for(index);
            style.show_polygon = matches!(p, Curve::BSpline(_) | Curve::Nurbs(_));
            style.show_points = style.show_polygon;
            curves.push(SceneCurve {
                name: Some(if k == 0 {
                    label
                } else {
                    format!("{label}, part {k}")
                }),
                curve: p,
                style,
            });
        }
    }
    let mut imported = Imported::of_file(file, curves, &left_out);
    imported.scene.unit = Some(unit);
    Ok(imported)
}

/// `#id NAME 'label'`, the label from the entity's name parameter when it has one.
fn label_of(inst: &Instance, id: u64) -> String {
    let r = &inst.records[0];
    match r.params.first() {
        Some(Value::Str(s)) if !s.is_empty() => format!("#{id} {} {s}", r.name),
        _ => format!("#{id} {}", r.name),
    }
}

fn refs(values: &[Value], out: &mut HashSet<u64>) {
    for v in values {
        match v {
            Value::Ref(id) => {
                out.insert(*id);
            }
            Value::List(l) | Value::Typed(_, l) => refs(l, out),
            _ => {}
        }
    }
}

const CURVES: &[&str] = &[
    "B_SPLINE_CURVE_WITH_KNOTS",
    "B_SPLINE_CURVE",
    "BEZIER_CURVE",
    "CIRCLE",
    "ELLIPSE",
    "LINE",
    "TRIMMED_CURVE",
    "COMPOSITE_CURVE",
];

fn is_curve(inst: &Instance) -> bool {
    inst.records
        .iter()
        .any(|r| CURVES.contains(&r.name.as_str()))
}

/// Byte offsets of line starts, for a line and column from an offset.
struct LineIndex(Vec<usize>);

impl LineIndex {
    fn new(text: &str) -> LineIndex {
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|(_, b)| *b == b'\n')
                .map(|(i, _)| i + 1),
        );
        LineIndex(starts)
    }

    fn at(&self, offset: usize) -> (u32, u32) {
        let line = self.0.partition_point(|&s| s <= offset).max(1);
        let col = offset - self.0[line - 1] + 1;
        (
            u32::try_from(line).unwrap_or(u32::MAX),
            u32::try_from(col).unwrap_or(u32::MAX),
        )
    }
}

/// A basis curve, before trimming.
#[derive(Debug, Clone)]
enum Basis {
    /// `P(t) = p + t·d`.
    Line { p: DVec3, d: DVec3 },
    /// `P(t) = c + a·cos t·x + b·sin t·y` (x, y unit and orthogonal; t in radians).
    Conic {
        c: DVec3,
        x: DVec3,
        y: DVec3,
        a: f64,
        b: f64,
    },
    /// A B-spline or NURBS curve with its own parameters.
    Spline(Curve),
    /// Pieces already joined (a trimmed or composite curve): only used whole.
    Joined(Vec<Curve>),
}

struct Model<'a> {
    file: &'a str,
    lines: &'a LineIndex,
    instances: &'a HashMap<u64, Instance>,
    max_points: u64,
    max_order: u64,
    max_depth: u64,
    /// Radians per plane angle unit.
    angle: f64,
    /// The instances being resolved (a cycle is refused).
    resolving: Vec<u64>,
}

type R<T> = Result<T, ImportError>;

impl<'a> Model<'a> {
    fn error(&self, id: u64, message: impl Into<String>) -> ImportError {
        let at = match self.instances.get(&id) {
            Some(inst) => {
                let names: Vec<&str> = inst.records.iter().map(|r| r.name.as_str()).collect();
                format!(
                    "#{id} {} (line {})",
                    names.join(" "),
                    self.lines.at(inst.offset).0
                )
            }
            None => format!("#{id}"),
        };
        ImportError::Entity {
            file: self.file.to_owned(),
            at,
            message: message.into(),
        }
    }

    fn inst(&self, from: u64, id: u64) -> R<&'a Instance> {
        self.instances
            .get(&id)
            .ok_or_else(|| self.error(from, format!("refers to #{id}, which is not in the file")))
    }

    /// The record `name` of instance `id` (simple or complex).
    fn record(&self, id: u64, name: &str) -> Option<&'a Record> {
        self.instances
            .get(&id)?
            .records
            .iter()
            .find(|r| r.name == name)
    }

    fn enter(&mut self, id: u64) -> R<()> {
        if self.resolving.contains(&id) {
            let chain: Vec<String> = self.resolving.iter().map(|i| format!("#{i}")).collect();
            return Err(self.error(
                id,
                format!("refers to itself ({} → #{id})", chain.join(" → ")),
            ));
        }
        if self.resolving.len() as u64 >= self.max_depth {
            return Err(self.error(
                id,
                limits::IMPORT_DEPTH
                    .check(self.resolving.len() as u64 + 1)
                    .err()
                    .map_or_else(String::new, |e| e.to_string()),
            ));
        }
        self.resolving.push(id);
        Ok(())
    }

    fn leave(&mut self) {
        self.resolving.pop();
    }

    fn real(&self, id: u64, v: Option<&Value>, what: &str) -> R<f64> {
        let x = match v {
            Some(Value::Real(x)) => *x,
            Some(Value::Int(n)) => *n as f64,
            Some(Value::Typed(_, inner)) if inner.len() == 1 => {
                return self.real(id, inner.first(), what);
            }
            other => {
                return Err(self.error(id, format!("{what}: a number expected, found {other:?}")));
            }
        };
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.error(id, format!("{what} is {x}")))
        }
    }

    fn int(&self, id: u64, v: Option<&Value>, what: &str) -> R<i64> {
        match v {
            Some(Value::Int(n)) => Ok(*n),
            other => Err(self.error(id, format!("{what}: an integer expected, found {other:?}"))),
        }
    }

    fn reference(&self, id: u64, v: Option<&Value>, what: &str) -> R<u64> {
        match v {
            Some(Value::Ref(r)) => Ok(*r),
            other => Err(self.error(id, format!("{what}: a reference expected, found {other:?}"))),
        }
    }

    fn list<'v>(&self, id: u64, v: Option<&'v Value>, what: &str) -> R<&'v [Value]> {
        match v {
            Some(Value::List(l)) => Ok(l),
            other => Err(self.error(id, format!("{what}: a list expected, found {other:?}"))),
        }
    }

    fn boolean(&self, id: u64, v: Option<&Value>, what: &str) -> R<bool> {
        match v {
            Some(Value::Enum(e)) if e.eq_ignore_ascii_case("T") => Ok(true),
            Some(Value::Enum(e)) if e.eq_ignore_ascii_case("F") => Ok(false),
            other => Err(self.error(id, format!("{what}: .T. or .F. expected, found {other:?}"))),
        }
    }

    /// The length unit's name, and the plane angle unit's radians (kept in `self.angle`).
    fn units(&mut self) -> R<String> {
        let mut unit = None;
        let mut ids: Vec<&u64> = self.instances.keys().collect();
        ids.sort_unstable();
        for &id in ids {
            let inst = &self.instances[&id];
            let has = |n: &str| inst.records.iter().any(|r| r.name == n);
            if has("LENGTH_UNIT") && unit.is_none() {
                unit = Some(Self::unit_name(inst));
            }
            if has("PLANE_ANGLE_UNIT")
                && let Some(r) = self.record(id, "CONVERSION_BASED_UNIT")
                && let Some(Value::Str(n)) = r.params.first()
                && (n.eq_ignore_ascii_case("DEGREE") || n.eq_ignore_ascii_case("DEGREES"))
            {
                self.angle = std::f64::consts::PI / 180.0;
            }
        }
        Ok(unit.unwrap_or_else(|| "unitless (the file names no length unit)".to_owned()))
    }

    fn unit_name(inst: &Instance) -> String {
        for r in &inst.records {
            match r.name.as_str() {
                "SI_UNIT" => {
                    let prefix = match r.params.first() {
                        Some(Value::Enum(p)) => p.to_ascii_lowercase(),
                        _ => String::new(),
                    };
                    let base = match r.params.get(1) {
                        Some(Value::Enum(b)) => b.to_ascii_lowercase(),
                        _ => "metre".to_owned(),
                    };
                    return format!("{prefix}{base}");
                }
                "CONVERSION_BASED_UNIT" => {
                    if let Some(Value::Str(n)) = r.params.first() {
                        return n.to_lowercase();
                    }
                }
                _ => {}
            }
        }
        "unknown length unit".to_owned()
    }

    fn point(&self, from: u64, id: u64) -> R<DVec3> {
        let inst = self.inst(from, id)?;
        let r = &inst.records[0];
        if r.name != "CARTESIAN_POINT" {
            return Err(self.error(id, format!("a CARTESIAN_POINT expected (used by #{from})")));
        }
        self.coords(id, r.params.get(1))
    }

    fn coords(&self, id: u64, v: Option<&Value>) -> R<DVec3> {
        let l = self.list(id, v, "coordinates")?;
        if l.is_empty() || l.len() > 3 {
            return Err(self.error(id, format!("{} coordinates", l.len())));
        }
        let mut p = [0.0; 3];
        for (k, c) in l.iter().enumerate() {
            p[k] = self.real(id, Some(c), "a coordinate")?;
        }
        Ok(DVec3::from_array(p))
    }

    fn direction(&self, from: u64, id: u64) -> R<DVec3> {
        let inst = self.inst(from, id)?;
        let r = &inst.records[0];
        if r.name != "DIRECTION" {
            return Err(self.error(id, format!("a DIRECTION expected (used by #{from})")));
        }
        self.coords(id, r.params.get(1))
    }

    /// An `AXIS2_PLACEMENT_3D` (or `_2D`): origin, x and y axes (unit, orthogonal).
    fn placement(&self, from: u64, id: u64) -> R<(DVec3, DVec3, DVec3)> {
        let inst = self.inst(from, id)?;
        let r = &inst.records[0];
        let origin = self.point(id, self.reference(id, r.params.get(1), "location")?)?;
        let (z, x_hint) = match r.name.as_str() {
            "AXIS2_PLACEMENT_3D" => {
                let z = match r.params.get(2) {
                    Some(Value::Ref(a)) => self.direction(id, *a)?,
                    _ => DVec3::Z,
                };
                let x = match r.params.get(3) {
                    Some(Value::Ref(a)) => Some(self.direction(id, *a)?),
                    _ => None,
                };
                (z, x)
            }
            "AXIS2_PLACEMENT_2D" => {
                let x = match r.params.get(2) {
                    Some(Value::Ref(a)) => Some(self.direction(id, *a)?),
                    _ => None,
                };
                (DVec3::Z, x)
            }
            other => {
                return Err(self.error(
                    id,
                    format!("an AXIS2_PLACEMENT expected, found {other} (used by #{from})"),
                ));
            }
        };
        let z = z
            .try_normalize()
            .ok_or_else(|| self.error(id, "the axis has length 0"))?;
        let hint = x_hint.unwrap_or(if z.x.abs() < 0.9 { DVec3::X } else { DVec3::Y });
        let x = (hint - z * hint.dot(z))
            .try_normalize()
            .ok_or_else(|| self.error(id, "the reference direction is parallel to the axis"))?;
        Ok((origin, x, z.cross(x)))
    }

    /// A basis curve.
    fn basis(&mut self, from: u64, id: u64) -> R<Basis> {
        let inst = self.inst(from, id)?;
        self.enter(id)?;
        let out = self.basis_of(id, inst);
        self.leave();
        out
    }

    fn basis_of(&mut self, id: u64, inst: &'a Instance) -> R<Basis> {
        if let Some(r) = self.record(id, "B_SPLINE_CURVE_WITH_KNOTS") {
            return self.spline(id, inst, r).map(Basis::Spline);
        }
        let r = &inst.records[0];
        let p = &r.params;
        match r.name.as_str() {
            "BEZIER_CURVE" => self.bezier(id, p).map(Basis::Spline),
            "LINE" => {
                let pnt = self.point(id, self.reference(id, p.get(1), "pnt")?)?;
                let vid = self.reference(id, p.get(2), "dir")?;
                let v = &self.inst(id, vid)?.records[0];
                if v.name != "VECTOR" {
                    return Err(self.error(vid, "a VECTOR expected"));
                }
                let d =
                    self.direction(vid, self.reference(vid, v.params.get(1), "orientation")?)?;
                let mag = self.real(vid, v.params.get(2), "magnitude")?;
                let d = d
                    .try_normalize()
                    .ok_or_else(|| self.error(vid, "the direction has length 0"))?;
                Ok(Basis::Line { p: pnt, d: d * mag })
            }
            "CIRCLE" | "ELLIPSE" => {
                let (c, x, y) = self.placement(id, self.reference(id, p.get(1), "position")?)?;
                let a = self.real(id, p.get(2), "radius")?;
                let b = if r.name == "ELLIPSE" {
                    self.real(id, p.get(3), "semi_axis_2")?
                } else {
                    a
                };
                if a <= 0.0 || b <= 0.0 {
                    return Err(self.error(id, format!("radii {a} and {b}: greater than 0")));
                }
                Ok(Basis::Conic { c, x, y, a, b })
            }
            "TRIMMED_CURVE" | "COMPOSITE_CURVE" => {
                let whole = self.whole_of(id, inst)?;
                whole
                    .map(Basis::Joined)
                    .ok_or_else(|| self.error(id, "an unbounded curve"))
            }
            "SURFACE_CURVE" | "SEAM_CURVE" | "INTERSECTION_CURVE" => {
                let c3 = self.reference(id, p.get(1), "curve_3d")?;
                self.basis(id, c3)
            }
            other => Err(self.error(id, format!("{other} is not a curve splinescope reads"))),
        }
    }

    fn check_count(&self, id: u64, n: usize) -> R<()> {
        if n as u64 > self.max_points {
            return Err(self.error(
                id,
                limits::POINTS
                    .check(n as u64)
                    .err()
                    .map_or_else(String::new, |e| e.to_string()),
            ));
        }
        Ok(())
    }

    fn control_points(&self, id: u64, v: Option<&Value>) -> R<Vec<DVec3>> {
        let l = self.list(id, v, "control_points_list")?;
        self.check_count(id, l.len())?;
        l.iter()
            .map(|p| self.point(id, self.reference(id, Some(p), "a control point")?))
            .collect()
    }

    fn degree(&self, id: u64, v: Option<&Value>) -> R<usize> {
        let d = self.int(id, v, "degree")?;
        if d < 1 || (d as u64).saturating_add(1) > self.max_order {
            return Err(self.error(
                id,
                if d < 1 {
                    format!("degree {d}: at least 1")
                } else {
                    limits::ORDER
                        .check(d as u64 + 1)
                        .err()
                        .map_or_else(String::new, |e| e.to_string())
                },
            ));
        }
        Ok(d as usize)
    }

    /// A `B_SPLINE_CURVE_WITH_KNOTS`, simple or in a complex instance with
    /// `B_SPLINE_CURVE` and `RATIONAL_B_SPLINE_CURVE`.
    fn spline(&self, id: u64, inst: &Instance, r: &Record) -> R<Curve> {
        let complex = inst.records.len() > 1;
        // Simple: (name, degree, points, form, closed, self_intersect, mults, knots,
        // spec); complex: B_SPLINE_CURVE(degree, points, form, closed, si) and
        // B_SPLINE_CURVE_WITH_KNOTS(mults, knots, spec).
        let (head, knots_at): (&[Value], usize) = if complex {
            let b = self
                .record(id, "B_SPLINE_CURVE")
                .ok_or_else(|| self.error(id, "a complex B-spline without B_SPLINE_CURVE"))?;
            (&b.params[..], 0)
        } else {
            (&r.params[1..], 6)
        };
        let degree = self.degree(id, head.first())?;
        let points = self.control_points(id, head.get(1))?;
        let mults = self.list(id, r.params.get(knots_at), "knot_multiplicities")?;
        let values = self.list(id, r.params.get(knots_at + 1), "knots")?;
        if mults.len() != values.len() {
            return Err(self.error(
                id,
                format!(
                    "{} knot multiplicities for {} knots",
                    mults.len(),
                    values.len()
                ),
            ));
        }
        let mut knots = Vec::new();
        for (m, v) in mults.iter().zip(values) {
            let m = self.int(id, Some(m), "a knot multiplicity")?;
            let v = self.real(id, Some(v), "a knot")?;
            if m < 1 || knots.len() as i64 + m > points.len() as i64 + degree as i64 + 1 {
                return Err(self.error(
                    id,
                    format!(
                        "knot {v} with multiplicity {m}: the multiplicities must add up to {} (points + degree + 1)",
                        points.len() + degree + 1
                    ),
                ));
            }
            knots.extend(std::iter::repeat_n(v, m as usize));
        }
        let wrap = |e: splinescope_core::geom::GeomError| self.error(id, e.to_string());
        match self.record(id, "RATIONAL_B_SPLINE_CURVE") {
            Some(rat) => {
                let w = self.list(id, rat.params.first(), "weights_data")?;
                let w: Vec<f64> = w
                    .iter()
                    .map(|x| self.real(id, Some(x), "a weight"))
                    .collect::<R<_>>()?;
                Nurbs::try_new(points, w, knots, degree + 1)
                    .map(Curve::Nurbs)
                    .map_err(wrap)
            }
            None => BSpline::try_new(points, knots, degree + 1)
                .map(Curve::BSpline)
                .map_err(wrap),
        }
    }

    /// A `BEZIER_CURVE`: `(n − 1)/p` Bézier pieces of degree `p` on the integers.
    fn bezier(&self, id: u64, p: &[Value]) -> R<Curve> {
        let degree = self.degree(id, p.get(1))?;
        let points = self.control_points(id, p.get(2))?;
        if points.len() < degree + 1 || (points.len() - 1) % degree != 0 {
            return Err(self.error(
                id,
                format!("{} control points: a piecewise Bézier curve of degree {degree} has k·{degree} + 1", points.len()),
            ));
        }
        let pieces = (points.len() - 1) / degree;
        let mut knots = vec![0.0; degree + 1];
        for k in 1..pieces {
            knots.extend(std::iter::repeat_n(k as f64, degree));
        }
        knots.extend(std::iter::repeat_n(pieces as f64, degree + 1));
        BSpline::try_new(points, knots, degree + 1)
            .map(Curve::BSpline)
            .map_err(|e| self.error(id, e.to_string()))
    }

    /// A curve drawn on its own: `None` for an unbounded line.
    fn whole(&mut self, id: u64) -> R<Option<Vec<Curve>>> {
        let inst = self.inst(id, id)?;
        self.enter(id)?;
        let out = self.whole_of(id, inst);
        self.leave();
        out
    }

    fn whole_of(&mut self, id: u64, inst: &'a Instance) -> R<Option<Vec<Curve>>> {
        let r = &inst.records[0];
        let p = &r.params;
        match r.name.as_str() {
            "TRIMMED_CURVE" => {
                let b = self.reference(id, p.get(1), "basis_curve")?;
                let basis = self.basis(id, b)?;
                let t1 = self.trim_parameter(id, &basis, p.get(2), "trim_1")?;
                let t2 = self.trim_parameter(id, &basis, p.get(3), "trim_2")?;
                let sense = self.boolean(id, p.get(4), "sense_agreement")?;
                Ok(Some(self.trimmed(id, &basis, t1, t2, sense)?))
            }
            "COMPOSITE_CURVE" => {
                let segs = self.list(id, p.get(1), "segments")?;
                let mut out: Vec<PathSegment> = Vec::new();
                let mut curves = Vec::new();
                for s in segs {
                    let sid = self.reference(id, Some(s), "a segment")?;
                    let seg = &self.inst(id, sid)?.records[0];
                    if seg.name != "COMPOSITE_CURVE_SEGMENT"
                        && seg.name != "REPARAMETRISED_COMPOSITE_CURVE_SEGMENT"
                    {
                        return Err(self.error(sid, "a COMPOSITE_CURVE_SEGMENT expected"));
                    }
                    let same = self.boolean(sid, seg.params.get(1), "same_sense")?;
                    let parent = self.reference(sid, seg.params.get(2), "parent_curve")?;
                    self.enter(sid)?;
                    let got = self.whole(parent);
                    self.leave();
                    let Some(pieces) = got? else {
                        return Err(self.error(sid, "its parent curve is unbounded"));
                    };
                    let mut segs: Vec<PathSegment> = pieces.iter().flat_map(segments_of).collect();
                    if !same {
                        segs = reversed(segs);
                    }
                    // A joint that does not meet starts a new curve.
                    if let (Some(last), Some(first)) = (out.last(), segs.first())
                        && Path::try_new(vec![last.clone(), first.clone()], false).is_err()
                    {
                        curves.push(self.path(id, std::mem::take(&mut out))?);
                    }
                    out.extend(segs);
                }
                if !out.is_empty() {
                    curves.push(self.path(id, out)?);
                }
                Ok(Some(curves))
            }
            "LINE" => Ok(None),
            _ => {
                let basis = self.basis_of(id, inst)?;
                Ok(Some(match basis {
                    Basis::Line { .. } => return Ok(None),
                    Basis::Conic { .. } => {
                        self.trimmed(id, &basis, 0.0, std::f64::consts::TAU, true)?
                    }
                    Basis::Spline(c) => vec![c],
                    Basis::Joined(c) => c,
                }))
            }
        }
    }

    /// A path of `segs`, closed when its ends meet (to rounding).
    fn path(&self, id: u64, segs: Vec<PathSegment>) -> R<Curve> {
        let a = segs.first().and_then(|s| s.points.first()).copied();
        let b = segs.last().and_then(|s| s.points.last()).copied();
        let closed = match (a, b) {
            (Some(a), Some(b)) => {
                segs.len() > 1 && a.distance(b) <= 1e-12 * (1.0 + a.abs().max_element())
            }
            _ => false,
        };
        Path::try_new(segs, closed)
            .map(Curve::Path)
            .map_err(|e| self.error(id, e.to_string()))
    }

    /// A trim select's parameter: a `PARAMETER_VALUE` when given, else the parameter of
    /// its point on the basis.
    fn trim_parameter(&self, id: u64, basis: &Basis, v: Option<&Value>, what: &str) -> R<f64> {
        let l = self.list(id, v, what)?;
        for x in l {
            if let Value::Typed(n, inner) = x
                && n == "PARAMETER_VALUE"
            {
                let t = self.real(id, inner.first(), what)?;
                return Ok(match basis {
                    Basis::Conic { .. } => t * self.angle,
                    _ => t,
                });
            }
        }
        for x in l {
            if let Value::Ref(p) = x {
                let q = self.point(id, *p)?;
                return self.parameter_of(id, basis, q);
            }
        }
        Err(self.error(id, format!("{what}: neither a parameter nor a point")))
    }

    /// The parameter of the point of `basis` nearest `q`.
    fn parameter_of(&self, id: u64, basis: &Basis, q: DVec3) -> R<f64> {
        Ok(match basis {
            Basis::Line { p, d } => (q - *p).dot(*d) / d.length_squared(),
            Basis::Conic { c, x, y, a, b } => {
                let r = q - *c;
                (r.dot(*y) / b).atan2(r.dot(*x) / a)
            }
            Basis::Spline(curve) => nearest(curve, q),
            Basis::Joined(_) => {
                return Err(self.error(id, "trimming a trimmed or composite curve by a point"));
            }
        })
    }

    /// `basis` from `t1` to `t2`, in its direction when `sense`, against it otherwise.
    fn trimmed(&self, id: u64, basis: &Basis, t1: f64, t2: f64, sense: bool) -> R<Vec<Curve>> {
        match basis {
            Basis::Line { p, d } => Ok(vec![self.path(
                id,
                vec![PathSegment {
                    points: vec![*p + *d * t1, *p + *d * t2].into(),
                    weights: None,
                }],
            )?]),
            Basis::Conic { c, x, y, a, b } => {
                let tau = std::f64::consts::TAU;
                let sweep = if sense {
                    let s = (t2 - t1).rem_euclid(tau);
                    if s == 0.0 { tau } else { s }
                } else {
                    let s = (t1 - t2).rem_euclid(tau);
                    -(if s == 0.0 { tau } else { s })
                };
                let full = sweep.abs() >= tau;
                let (start, sweep_pos) = if sweep > 0.0 {
                    (t1, sweep)
                } else {
                    (t1 + sweep, -sweep)
                };
                let map = |u: DVec2| *c + *x * (a * u.x) + *y * (b * u.y);
                let mut segs: Vec<PathSegment> = crate::svg::geometry::unit_arc(start, sweep_pos)
                    .into_iter()
                    .map(|s| PathSegment {
                        points: s.points.iter().map(|&u| map(u)).collect(),
                        weights: s.weights,
                    })
                    .collect();
                if sweep < 0.0 {
                    segs = reversed(segs);
                }
                let path = Path::try_new(segs, full).map_err(|e| self.error(id, e.to_string()))?;
                Ok(vec![Curve::Path(path)])
            }
            Basis::Spline(curve) => {
                if !sense {
                    let fwd = self.trimmed(id, basis, t2, t1, true)?;
                    let segs: Vec<PathSegment> = fwd.iter().flat_map(segments_of).collect();
                    return Ok(vec![self.path(id, reversed(segs))?]);
                }
                let (lo, hi) = curve.domain();
                let segs = if t1 <= t2 {
                    piece(curve, t1, t2)
                } else {
                    // Across a closed curve's seam.
                    let mut s = piece(curve, t1, hi);
                    s.extend(piece(curve, lo, t2));
                    s
                };
                if segs.is_empty() {
                    return Err(self.error(id, format!("the trimmed range [{t1}, {t2}] is empty")));
                }
                Ok(vec![self.path(id, segs)?])
            }
            Basis::Joined(_) => Err(self.error(id, "trimming a trimmed or composite curve")),
        }
    }

    /// An `EDGE_CURVE`: its geometry between its vertices (the whole curve when they are
    /// one point of a closed curve).
    fn edge(&mut self, id: u64) -> R<Option<Vec<Curve>>> {
        let r = &self.inst(id, id)?.records[0];
        let vertex = |m: &Model<'_>, v: Option<&Value>, what: &str| -> R<DVec3> {
            let vid = m.reference(id, v, what)?;
            let vr = &m.inst(id, vid)?.records[0];
            if vr.name != "VERTEX_POINT" {
                return Err(m.error(vid, "a VERTEX_POINT expected"));
            }
            m.point(vid, m.reference(vid, vr.params.get(1), "vertex_geometry")?)
        };
        let a = vertex(self, r.params.get(1), "edge_start")?;
        let b = vertex(self, r.params.get(2), "edge_end")?;
        let g = self.reference(id, r.params.get(3), "edge_geometry")?;
        let same = self.boolean(id, r.params.get(4), "same_sense")?;
        self.enter(id)?;
        let basis = self.basis(id, g);
        self.leave();
        let basis = basis?;
        let closed_loop = a.distance(b) <= 1e-9 * (1.0 + a.abs().max_element());
        let (ta, tb) = (
            self.parameter_of(id, &basis, a)?,
            self.parameter_of(id, &basis, b)?,
        );
        let curves = match &basis {
            Basis::Conic { .. } if closed_loop => {
                self.trimmed(id, &basis, ta, ta + std::f64::consts::TAU, same)?
            }
            Basis::Spline(c) if closed_loop => {
                let (lo, hi) = c.domain();
                let segs = piece(c, lo, hi);
                let segs = if same { segs } else { reversed(segs) };
                vec![self.path(id, segs)?]
            }
            _ if same => self.trimmed(id, &basis, ta, tb, true)?,
            _ => self.trimmed(id, &basis, ta, tb, false)?,
        };
        Ok(Some(curves))
    }
}

/// A curve's segments as path segments.
fn segments_of(c: &Curve) -> Vec<PathSegment> {
    match c {
        Curve::Path(p) => p.segments().to_vec(),
        other => {
            let (lo, hi) = other.domain();
            piece(other, lo, hi)
        }
    }
}

/// The exact Bézier pieces of `curve` between parameters `t1 < t2`.
fn piece(curve: &Curve, t1: f64, t2: f64) -> Vec<PathSegment> {
    let mut out = Vec::new();
    for s in curve.lower() {
        let (a, b) = (s.t0.max(t1), s.t1.min(t2));
        if a >= b {
            continue;
        }
        let (u0, u1) = (s.local_u(a), s.local_u(b));
        let (u0, u1) = (u0.clamp(0.0, 1.0), u1.clamp(0.0, 1.0));
        match &s.weights {
            None => {
                let sub = if (u0, u1) == (0.0, 1.0) {
                    s.bezier.clone()
                } else {
                    s.bezier.subsegment(u0, u1)
                };
                out.push(PathSegment {
                    points: sub.points().to_vec().into(),
                    weights: None,
                });
            }
            Some(weights) if (u0, u1) == (0.0, 1.0) => out.push(PathSegment {
                points: s.points().into(),
                weights: Some(weights.clone()),
            }),
            Some(_) => {
                // The homogeneous parts (A = w·P, W = w) cut by de Casteljau, then
                // divided: the weights of a piece of a curve with positive weights are
                // positive (convex combinations of them).
                let (h, w) = s.homogeneous();
                let (h, w) = (h.subsegment(u0, u1), w.subsegment(u0, u1));
                let weights: Vec<f64> = w.points().iter().map(|p| p.x).collect();
                out.push(PathSegment {
                    points: h
                        .points()
                        .iter()
                        .zip(&weights)
                        .map(|(p, w)| *p / *w)
                        .collect(),
                    weights: Some(weights),
                });
            }
        }
    }
    out
}

/// Segments in the opposite direction.
fn reversed(segs: Vec<PathSegment>) -> Vec<PathSegment> {
    segs.into_iter()
        .rev()
        .map(|mut s| {
            s.points.reverse();
            if let Some(w) = &mut s.weights {
                w.reverse();
            }
            s
        })
        .collect()
}

/// The parameter of `curve`'s point nearest `q`: the nearest of dense samples, refined by
/// Newton's method on `(C(t) − q)·C′(t) = 0` within the sample's neighbours.
fn nearest(curve: &Curve, q: DVec3) -> f64 {
    let (lo, hi) = curve.domain();
    let n = 64 * curve.lower().len().max(1);
    let at = |k: usize| lo + (hi - lo) * k as f64 / n as f64;
    let (mut best, mut dist) = (lo, f64::INFINITY);
    let mut best_k = 0;
    for k in 0..=n {
        let d = curve.eval(at(k)).distance_squared(q);
        if d < dist {
            (best, dist, best_k) = (at(k), d, k);
        }
    }
    let (a, b) = (at(best_k.saturating_sub(1)), at((best_k + 1).min(n)));
    let mut t = best;
    for _ in 0..50 {
        let (p, d1, d2) = (
            curve.eval(t),
            curve.eval_deriv(t),
            curve.eval_second_deriv(t),
        );
        let f = (p - q).dot(d1);
        let df = d1.dot(d1) + (p - q).dot(d2);
        if df <= 0.0 || !df.is_finite() {
            break;
        }
        let next = (t - f / df).clamp(a, b);
        if (next - t).abs() <= 1e-16 * (1.0 + t.abs()) {
            t = next;
            break;
        }
        t = next;
    }
    if curve.eval(t).distance_squared(q) <= dist {
        t
    } else {
        best
    }
}
