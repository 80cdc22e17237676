//! DXF in and out, through the `dxf` crate (ASCII and binary DXF).
//!
//! In: `SPLINE` (its degree, knots, weights and control points as they are: a B-spline or
//! a NURBS curve; one given only by fit points is refused naming its handle), `LINE`,
//! `ARC`, `CIRCLE` and `ELLIPSE` (exact rational quadratics of at most 90° each),
//! `LWPOLYLINE` and `POLYLINE` (bulges as exact arcs, the closed flag, 3D vertices),
//! `INSERT` of blocks (scale, rotation, translation, column and row arrays; nested, each
//! level bounded), colours by entity, by layer or by block (the AutoCAD Colour Index to
//! RGB, or the entity's true colour). Entities in the object coordinate system (arcs,
//! circles, polylines, inserts) are mapped to the world by the arbitrary axis algorithm.
//! Paper space, text, hatches, dimensions, meshes and the rest are left out with one
//! warning that counts them.
//!
//! Out ([`write()`]): every curve of a scene as one exact `SPLINE` (its [`NurbsForm`]: the
//! knots and weights the curve has; a family that is not a B-spline lowers exactly to
//! one), on a layer named after the curve, in its colour. The file is binary DXF, which
//! holds each `f64` as its 8 bytes, so a scene written and read back evaluates to the same
//! points bit for bit; ASCII DXF as the `dxf` crate writes it keeps 12 decimals
//! ([`write_ascii`]).

use std::collections::BTreeMap;

use dxf::entities::{Entity, EntityType};
use dxf::{Color as DxfColor, Drawing, Point};
use glam::{DAffine3, DMat3, DVec2, DVec3};
use splinescope_core::geom::{BSpline, Curve, Nurbs, NurbsForm, Path, PathSegment};
use splinescope_encoding::Color;
use splinescope_io::limits;
use splinescope_scene::format::{Scene, SceneCurve, Style};

use crate::svg::geometry::{Seg, svg_arc, unit_arc};
use crate::{ImportError, Imported};

/// Reads DXF `bytes` (ASCII or binary) as a scene.
///
/// # Errors
/// [`ImportError::Io`] for a file the `dxf` crate cannot read, [`ImportError::Entity`]
/// for an entity whose numbers are wrong (naming its type and handle), and
/// [`ImportError::Limit`] past a documented limit.
pub fn read(bytes: &[u8], file: &str) -> Result<Imported, ImportError> {
    let limit = |l: limits::Limit| {
        l.value().map_err(|source| ImportError::Limit {
            file: file.to_owned(),
            source,
        })
    };
    // The `dxf` crate is not written for hostile input: a panic inside it is this file's
    // syntax error, not the program's end.
    let loaded = crate::guarded(|| Drawing::load(&mut &bytes[..]));
    let drawing = match loaded {
        Some(Ok(d)) => d,
        Some(Err(e)) => return Err(syntax(file, e.to_string())),
        None => {
            return Err(syntax(
                file,
                "the DXF reader failed on this file".to_owned(),
            ));
        }
    };
    let mut reader = Reader {
        file,
        layers: drawing
            .layers()
            .map(|l| (l.name.to_lowercase(), l.color.index()))
            .collect(),
        blocks: drawing
            .blocks()
            .map(|b| (b.name.to_lowercase(), b))
            .collect(),
        curves: Vec::new(),
        left_out: BTreeMap::new(),
        visited: 0,
        max_visited: limit(limits::IMPORT_ELEMENTS)?,
        max_depth: limit(limits::IMPORT_DEPTH)?,
        max_curves: limit(limits::CURVES)?,
        max_points: limit(limits::POINTS)?,
        max_order: limit(limits::ORDER)?,
        inserting: Vec::new(),
    };
    for e in drawing.entities() {
        if e.common.is_in_paper_space {
            *reader
                .left_out
                .entry("in paper space".to_owned())
                .or_default() += 1;
            continue;
        }
        reader.entity(e, DAffine3::IDENTITY, None, 0)?;
    }
    Ok(Imported::of_file(file, reader.curves, &reader.left_out))
}

/// The `dxf` crate's errors carry their own place ("at line/offset N").
fn syntax(file: &str, message: String) -> ImportError {
    ImportError::Io {
        file: file.to_owned(),
        message: format!("not a DXF file this reader can read: {message}"),
    }
}

struct Reader<'a> {
    file: &'a str,
    /// Layer name (lower case) → its colour index.
    layers: BTreeMap<String, Option<u8>>,
    /// Block name (lower case) → the block.
    blocks: BTreeMap<String, &'a dxf::Block>,
    curves: Vec<SceneCurve>,
    left_out: BTreeMap<String, u64>,
    /// Entities visited, inserted blocks' copies included.
    visited: u64,
    max_visited: u64,
    max_depth: u64,
    max_curves: u64,
    max_points: u64,
    max_order: u64,
    /// The blocks being inserted, outermost first (a cycle is refused).
    inserting: Vec<String>,
}

/// One curve's pieces before they become a path: 3D segments in the entity's own frame.
struct Pieces {
    segments: Vec<PathSegment>,
    closed: bool,
}

fn v3(p: &Point) -> DVec3 {
    DVec3::new(p.x, p.y, p.z)
}

fn vec3(v: &dxf::Vector) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}

/// The object coordinate system of extrusion direction `n`: the arbitrary axis algorithm
/// of the DXF reference (`Ax = Wy × N` when `N` is within 1/64 of the world z axis, else
/// `Wz × N`; `Ay = N × Ax`), as the map from OCS to world coordinates.
fn ocs(n: DVec3) -> Option<DMat3> {
    let n = n.try_normalize()?;
    let ax = if n.x.abs() < 1.0 / 64.0 && n.y.abs() < 1.0 / 64.0 {
        DVec3::Y.cross(n)
    } else {
        DVec3::Z.cross(n)
    }
    .normalize();
    let ay = n.cross(ax);
    Some(DMat3::from_cols(ax, ay, n))
}

/// 2D segments (arcs as SVG arcs give them) lifted to 3D by `m`.
fn lifted(segs: &[Seg], m: DAffine3, z: f64) -> Vec<PathSegment> {
    segs.iter()
        .map(|s| PathSegment {
            points: s
                .points
                .iter()
                .map(|p| m.transform_point3(p.extend(z)))
                .collect(),
            weights: s.weights.clone(),
        })
        .collect()
}

/// The arc of a polyline from `a` to `b` with bulge `bulge` (the tangent of a quarter of
/// its included angle, positive counter-clockwise), as exact rational quadratics.
fn bulge_arc(a: DVec2, b: DVec2, bulge: f64) -> Vec<Seg> {
    if bulge == 0.0 || a == b {
        return vec![Seg {
            points: vec![a, b],
            weights: None,
        }];
    }
    let theta = 4.0 * bulge.atan();
    let half = 0.5 * (b - a).length();
    let r = half / (0.5 * theta).sin().abs();
    svg_arc(
        a,
        b,
        r,
        r,
        0.0,
        theta.abs() > std::f64::consts::PI,
        theta > 0.0,
    )
}

/// The counter-clockwise sweep from `start` to `end` (radians) in `(0, 2π]`: equal angles
/// are a whole turn.
fn ccw_sweep(start: f64, end: f64) -> f64 {
    let s = (end - start).rem_euclid(std::f64::consts::TAU);
    if s == 0.0 { std::f64::consts::TAU } else { s }
}

/// The AutoCAD Colour Index's RGB: 1–9 the named colours, 10–249 the 24 hues of 15° at
/// five values, each full and half saturated, 250–255 greys. 7 (white on a dark
/// background, black on a light one) is black: scenes open on white.
#[must_use]
pub fn aci_rgb(index: u8) -> [u8; 3] {
    match index {
        0 | 7 => [0, 0, 0],
        1 => [255, 0, 0],
        2 => [255, 255, 0],
        3 => [0, 255, 0],
        4 => [0, 255, 255],
        5 => [0, 0, 255],
        6 => [255, 0, 255],
        8 => [128, 128, 128],
        9 => [192, 192, 192],
        250..=255 => {
            let g = [51, 80, 105, 130, 190, 255][usize::from(index - 250)];
            [g, g, g]
        }
        _ => {
            let hue = f64::from(index / 10 - 1) * 15.0;
            let k = index % 10;
            let value = [1.0, 0.65, 0.5, 0.3, 0.15][usize::from(k / 2)];
            let half = k % 2 == 1;
            // The pure hue's channels in [0, 1].
            let channel = |offset: f64| {
                let h = (hue + offset).rem_euclid(360.0);
                let c = if h < 60.0 {
                    1.0
                } else if h < 120.0 {
                    (120.0 - h) / 60.0
                } else if h < 240.0 {
                    0.0
                } else if h < 300.0 {
                    (h - 240.0) / 60.0
                } else {
                    1.0
                };
                let c = if half { 0.5 + 0.5 * c } else { c };
                (255.0 * value * c).floor() as u8
            };
            // Red peaks at 0°, green at 120°, blue at 240°.
            [channel(0.0), channel(-120.0), channel(-240.0)]
        }
    }
}

impl<'a> Reader<'a> {
    fn entity_error(&self, e: &Entity, message: impl Into<String>) -> ImportError {
        ImportError::Entity {
            file: self.file.to_owned(),
            at: format!("{} (handle {})", kind(e), e.common.handle.as_string()),
            message: message.into(),
        }
    }

    fn limit_error(&self, e: &Entity, l: limits::Limit, found: u64) -> ImportError {
        self.entity_error(
            e,
            l.check(found)
                .err()
                .map_or_else(|| format!("{found} {}", l.what), |x| x.to_string()),
        )
    }

    /// The colour of `e`: its true colour, its index, its layer's, or (by block) the
    /// inserting entity's.
    fn color(&self, e: &Entity, by_block: Option<[u8; 3]>) -> [u8; 3] {
        let c = e.common.color_24_bit;
        if c > 0 {
            let c = c as u32;
            return [(c >> 16) as u8, (c >> 8) as u8, c as u8];
        }
        let layer = || {
            self.layers
                .get(&e.common.layer.to_lowercase())
                .copied()
                .flatten()
                .map_or([0, 0, 0], aci_rgb)
        };
        let color: &DxfColor = &e.common.color;
        if color.is_by_layer() {
            layer()
        } else if color.is_by_block() {
            by_block.unwrap_or_else(layer)
        } else {
            color.index().map_or_else(layer, aci_rgb)
        }
    }

    fn entity(
        &mut self,
        e: &'a Entity,
        m: DAffine3,
        by_block: Option<[u8; 3]>,
        depth: u64,
    ) -> Result<(), ImportError> {
        self.visited += 1;
        if self.visited > self.max_visited {
            return Err(self.limit_error(e, limits::IMPORT_ELEMENTS, self.visited));
        }
        let color = self.color(e, by_block);
        let ocs_of = |n: &dxf::Vector| {
            ocs(vec3(n)).ok_or_else(|| self.entity_error(e, "extrusion direction (0, 0, 0)"))
        };
        // A radius, an axis ratio or an angle that is not a usable number is the entity's
        // error, named, never a curve drawn from it.
        let positive = |what: &str, x: f64| {
            if x.is_finite() && x > 0.0 {
                Ok(x)
            } else {
                Err(self.entity_error(e, format!("{what} {x}: a finite number greater than 0")))
            }
        };
        let finite = |what: &str, x: f64| {
            if x.is_finite() {
                Ok(x)
            } else {
                Err(self.entity_error(e, format!("{what} {x}: not a finite number")))
            }
        };
        let pieces: Vec<Pieces> = match &e.specific {
            EntityType::Spline(s) => {
                let curve = self.spline(e, s)?;
                let curve = transformed(curve, m)
                    .map_err(|x| self.entity_error(e, format!("placed by its inserts: {x}")))?;
                return self.push(e, curve, color);
            }
            EntityType::Line(l) => vec![Pieces {
                segments: vec![PathSegment {
                    points: vec![v3(&l.p1), v3(&l.p2)].into(),
                    weights: None,
                }],
                closed: false,
            }],
            EntityType::Arc(a) => {
                let frame = ocs_of(&a.normal)?;
                let r = positive("radius", a.radius)?;
                let s = finite("start angle", a.start_angle)?.to_radians();
                let t = finite("end angle", a.end_angle)?.to_radians();
                vec![Pieces {
                    segments: circle_piece(frame, v3(&a.center), r, s, ccw_sweep(s, t)),
                    closed: false,
                }]
            }
            EntityType::Circle(c) => {
                let frame = ocs_of(&c.normal)?;
                let r = positive("radius", c.radius)?;
                vec![Pieces {
                    segments: circle_piece(frame, v3(&c.center), r, 0.0, std::f64::consts::TAU),
                    closed: true,
                }]
            }
            EntityType::Ellipse(el) => {
                let major = vec3(&el.major_axis);
                let n = vec3(&el.normal)
                    .try_normalize()
                    .ok_or_else(|| self.entity_error(e, "extrusion direction (0, 0, 0)"))?;
                positive("major axis length", major.length())?;
                let ratio = positive("minor axis ratio", el.minor_axis_ratio)?;
                let minor = n.cross(major) * ratio;
                let sweep = ccw_sweep(
                    finite("start parameter", el.start_parameter)?,
                    finite("end parameter", el.end_parameter)?,
                );
                let map = DAffine3::from_mat3_translation(
                    DMat3::from_cols(major, minor, n),
                    v3(&el.center),
                );
                vec![Pieces {
                    segments: lifted(&unit_arc(el.start_parameter, sweep), map, 0.0),
                    closed: sweep >= std::f64::consts::TAU,
                }]
            }
            EntityType::LwPolyline(p) => {
                let frame = ocs_of(&p.extrusion_direction)?;
                let v: Vec<(DVec2, f64)> = p
                    .vertices
                    .iter()
                    .map(|v| (DVec2::new(v.x, v.y), v.bulge))
                    .collect();
                let map = DAffine3::from_mat3(frame);
                if let Some(&(_, b)) = v.iter().find(|(_, b)| !b.is_finite()) {
                    finite("bulge", b)?;
                }
                vec![polyline(&v, p.is_closed(), map, e.common.elevation)]
            }
            EntityType::Polyline(p) => {
                if p.is_3d_polygon_mesh() || p.is_polyface_mesh() {
                    *self.left_out.entry("meshes".to_owned()).or_default() += 1;
                    return Ok(());
                }
                let verts: Vec<&dxf::entities::Vertex> = p
                    .vertices()
                    .filter(|v| !v.is_spline_frame_control_point())
                    .collect();
                if p.is_3d_polyline() {
                    let pts: Vec<DVec3> = verts.iter().map(|v| v3(&v.location)).collect();
                    vec![polyline_3d(&pts, p.is_closed())]
                } else {
                    let frame = ocs_of(&p.normal)?;
                    let v: Vec<(DVec2, f64)> = verts
                        .iter()
                        .map(|v| (DVec2::new(v.location.x, v.location.y), v.bulge))
                        .collect();
                    if let Some(&(_, b)) = v.iter().find(|(_, b)| !b.is_finite()) {
                        finite("bulge", b)?;
                    }
                    vec![polyline(
                        &v,
                        p.is_closed(),
                        DAffine3::from_mat3(frame),
                        p.location.z,
                    )]
                }
            }
            EntityType::Insert(i) => return self.insert(e, i, m, color, depth),
            _ => {
                *self.left_out.entry(kind(e).to_owned()).or_default() += 1;
                return Ok(());
            }
        };
        for p in pieces {
            if p.segments.is_empty() {
                continue;
            }
            let count: u64 = p.segments.iter().map(|s| s.points.len() as u64).sum();
            if count > self.max_points {
                return Err(self.limit_error(e, limits::POINTS, count));
            }
            let segments = p
                .segments
                .into_iter()
                .map(|s| PathSegment {
                    points: s.points.iter().map(|&q| m.transform_point3(q)).collect(),
                    weights: s.weights,
                })
                .collect();
            let path = Path::try_new(segments, p.closed)
                .map_err(|x| self.entity_error(e, x.to_string()))?;
            self.push(e, Curve::Path(path), color)?;
        }
        Ok(())
    }

    fn push(&mut self, e: &Entity, curve: Curve, rgb: [u8; 3]) -> Result<(), ImportError> {
        if self.curves.len() as u64 >= self.max_curves {
            return Err(self.limit_error(e, limits::CURVES, self.curves.len() as u64 + 1));
        }
        let mut style = Style::default_for(self.curves.len());
        style.color = Color::from_rgba8([rgb[0], rgb[1], rgb[2], 255]);
        style.show_polygon = matches!(curve, Curve::BSpline(_) | Curve::Nurbs(_));
        style.show_points = style.show_polygon;
        self.curves.push(SceneCurve {
            name: Some(format!(
                "{}/{} {}",
                e.common.layer,
                kind(e),
                e.common.handle.as_string()
            )),
            curve,
            style,
        });
        Ok(())
    }

    /// A `SPLINE` as the B-spline or NURBS curve it stores.
    fn spline(&self, e: &Entity, s: &dxf::entities::Spline) -> Result<Curve, ImportError> {
        let points: Vec<DVec3> = s.control_points.iter().map(v3).collect();
        if points.is_empty() {
            return Err(self.entity_error(
                e,
                if s.fit_points.is_empty() {
                    "no control points".to_owned()
                } else {
                    format!(
                        "given only by {} fit points: splinescope reads the control points, knots and weights a spline stores, not a fit it would have to redo",
                        s.fit_points.len()
                    )
                },
            ));
        }
        if points.len() as u64 > self.max_points {
            return Err(self.limit_error(e, limits::POINTS, points.len() as u64));
        }
        let degree = u64::try_from(s.degree_of_curve)
            .map_err(|_| self.entity_error(e, format!("degree {}", s.degree_of_curve)))?;
        if degree + 1 > self.max_order {
            return Err(self.limit_error(e, limits::ORDER, degree + 1));
        }
        let order = degree as usize + 1;
        let knots = s.knot_values.clone();
        let wrap = |x: splinescope_core::geom::GeomError| self.entity_error(e, x.to_string());
        if s.weight_values.is_empty() || s.weight_values.iter().all(|&w| w == 1.0) {
            if !s.weight_values.is_empty() && s.weight_values.len() != points.len() {
                return Err(self.entity_error(
                    e,
                    format!(
                        "{} weights for {} control points",
                        s.weight_values.len(),
                        points.len()
                    ),
                ));
            }
            BSpline::try_new(points, knots, order)
                .map(Curve::BSpline)
                .map_err(wrap)
        } else {
            Nurbs::try_new(points, s.weight_values.clone(), knots, order)
                .map(Curve::Nurbs)
                .map_err(wrap)
        }
    }

    fn insert(
        &mut self,
        e: &'a Entity,
        i: &'a dxf::entities::Insert,
        m: DAffine3,
        color: [u8; 3],
        depth: u64,
    ) -> Result<(), ImportError> {
        let name = i.name.to_lowercase();
        if depth + 1 > self.max_depth {
            return Err(self.limit_error(e, limits::IMPORT_DEPTH, depth + 1));
        }
        if self.inserting.contains(&name) {
            return Err(self.entity_error(
                e,
                format!(
                    "block {:?} inserts itself ({} → {})",
                    i.name,
                    self.inserting.join(" → "),
                    i.name
                ),
            ));
        }
        let Some(&block) = self.blocks.get(&name) else {
            return Err(self.entity_error(e, format!("block {:?} is not in the file", i.name)));
        };
        let frame = ocs(vec3(&i.extrusion_direction))
            .ok_or_else(|| self.entity_error(e, "extrusion direction (0, 0, 0)"))?;
        let scale = DVec3::new(i.x_scale_factor, i.y_scale_factor, i.z_scale_factor);
        if !scale.is_finite() || scale.x * scale.y * scale.z == 0.0 {
            return Err(self.entity_error(e, format!("scale factors {scale}: finite, not 0")));
        }
        let copies = u64::from(i.column_count.max(1) as u16) * u64::from(i.row_count.max(1) as u16);
        if copies > self.max_visited {
            return Err(self.limit_error(e, limits::IMPORT_ELEMENTS, copies));
        }
        if !(i.rotation.is_finite() && i.column_spacing.is_finite() && i.row_spacing.is_finite()) {
            return Err(self.entity_error(
                e,
                format!(
                    "rotation {}, column spacing {}, row spacing {}: finite numbers",
                    i.rotation, i.column_spacing, i.row_spacing
                ),
            ));
        }
        let rotation = DMat3::from_rotation_z(i.rotation.to_radians());
        self.inserting.push(name);
        for row in 0..i.row_count.max(1) {
            for col in 0..i.column_count.max(1) {
                let offset = DVec3::new(
                    f64::from(col) * i.column_spacing,
                    f64::from(row) * i.row_spacing,
                    0.0,
                );
                // Block coordinates → scaled about the base point → rotated → moved to
                // the insertion point (in the insert's OCS) → world.
                let local = DAffine3::from_mat3(frame)
                    * DAffine3::from_translation(v3(&i.location))
                    * DAffine3::from_mat3(rotation)
                    * DAffine3::from_translation(offset)
                    * DAffine3::from_scale(scale)
                    * DAffine3::from_translation(-v3(&block.base_point));
                for child in &block.entities {
                    self.entity(child, m * local, Some(color), depth + 1)?;
                }
            }
        }
        self.inserting.pop();
        Ok(())
    }
}

/// A circular arc in an OCS `frame`: centre `c` (OCS coordinates), radius `r`, from angle
/// `a0` counter-clockwise over `sweep` radians.
fn circle_piece(frame: DMat3, c: DVec3, r: f64, a0: f64, sweep: f64) -> Vec<PathSegment> {
    let map = DAffine3::from_mat3(frame)
        * DAffine3::from_translation(c)
        * DAffine3::from_scale(DVec3::new(r, r, 1.0));
    lifted(&unit_arc(a0, sweep), map, 0.0)
}

/// A 2D polyline with bulges in the OCS `map`, at height `z`.
fn polyline(v: &[(DVec2, f64)], closed: bool, map: DAffine3, z: f64) -> Pieces {
    let mut segs = Vec::new();
    let n = v.len();
    let legs = if closed { n } else { n.saturating_sub(1) };
    for k in 0..legs {
        let (a, bulge) = v[k];
        let (b, _) = v[(k + 1) % n];
        if a == b {
            continue;
        }
        // Bulges are checked finite by the caller.
        segs.extend(bulge_arc(a, b, bulge));
    }
    // The last leg of a closed polyline ends exactly where it started.
    Pieces {
        segments: lifted(&segs, map, z),
        closed: closed && !segs.is_empty(),
    }
}

/// A 3D polyline: straight legs.
fn polyline_3d(pts: &[DVec3], closed: bool) -> Pieces {
    let mut segments = Vec::new();
    let n = pts.len();
    let legs = if closed { n } else { n.saturating_sub(1) };
    for k in 0..legs {
        let (a, b) = (pts[k], pts[(k + 1) % n]);
        if a != b {
            segments.push(PathSegment {
                points: vec![a, b].into(),
                weights: None,
            });
        }
    }
    Pieces {
        closed: closed && !segments.is_empty(),
        segments,
    }
}

/// `curve` (a B-spline or NURBS curve) mapped by the affine `m` (its control points; the
/// weights and knots do not change).
///
/// # Errors
/// The map sends a control point past the largest double (the curve's error says which).
fn transformed(curve: Curve, m: DAffine3) -> Result<Curve, splinescope_core::geom::GeomError> {
    if m == DAffine3::IDENTITY {
        return Ok(curve);
    }
    let f = NurbsForm::of(&curve);
    let points = f.points.iter().map(|&p| m.transform_point3(p)).collect();
    let order = f.degree + 1;
    match f.weights {
        Some(w) => Nurbs::try_new(points, w, f.knots, order).map(Curve::Nurbs),
        None => BSpline::try_new(points, f.knots, order).map(Curve::BSpline),
    }
}

/// The DXF name of an entity's type.
fn kind(e: &Entity) -> &'static str {
    match &e.specific {
        EntityType::Spline(_) => "SPLINE",
        EntityType::Line(_) => "LINE",
        EntityType::Arc(_) => "ARC",
        EntityType::Circle(_) => "CIRCLE",
        EntityType::Ellipse(_) => "ELLIPSE",
        EntityType::LwPolyline(_) => "LWPOLYLINE",
        EntityType::Polyline(_) => "POLYLINE",
        EntityType::Insert(_) => "INSERT",
        EntityType::Text(_) | EntityType::MText(_) => "texts",
        EntityType::ModelPoint(_) => "points",
        EntityType::Solid(_) | EntityType::Face3D(_) => "faces",
        _ => "other entities",
    }
}

/// Why a scene cannot be written as DXF.
#[derive(Debug, thiserror::Error)]
#[error("writing DXF: {0}")]
pub struct WriteError(String);

/// The scene as a binary DXF file: one exact `SPLINE` per curve (see the [module
/// docs](self)).
///
/// # Errors
/// [`WriteError`] when the `dxf` crate cannot write the drawing.
pub fn write(scene: &Scene) -> Result<Vec<u8>, WriteError> {
    save(scene, false)
}

/// [`write()`] as ASCII DXF (numbers to 12 decimals, so not bit for bit).
///
/// # Errors
/// [`WriteError`] when the `dxf` crate cannot write the drawing.
pub fn write_ascii(scene: &Scene) -> Result<Vec<u8>, WriteError> {
    save(scene, true)
}

fn save(scene: &Scene, ascii: bool) -> Result<Vec<u8>, WriteError> {
    let drawing = drawing(scene);
    let mut out = Vec::new();
    let saved = if ascii {
        drawing.save(&mut out)
    } else {
        drawing.save_binary(&mut out)
    };
    saved.map_err(|e| WriteError(e.to_string()))?;
    Ok(out)
}

/// A layer name from a curve's name: DXF refuses `<>/\":;?*|=,` and the backquote.
fn layer_name(name: Option<&str>, index: usize) -> String {
    let base = name.map_or_else(|| format!("curve {index}"), str::to_owned);
    let clean: String = base
        .chars()
        .map(|c| {
            if "<>/\\\":;?*|=,`".contains(c) || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    format!("{index:04} {clean}")
}

fn drawing(scene: &Scene) -> Drawing {
    let mut d = Drawing::new();
    d.header.version = dxf::enums::AcadVersion::R2018;
    for (i, c) in scene.curves.iter().enumerate() {
        let f = NurbsForm::of(&c.curve);
        let name = layer_name(c.name.as_deref(), i);
        let [r, g, b, _] = c.style.color.to_rgba8();
        let rgb = (i32::from(r) << 16) | (i32::from(g) << 8) | i32::from(b);
        let layer = dxf::tables::Layer {
            name: name.clone(),
            ..Default::default()
        };
        d.add_layer(layer);
        let planar = f.points.iter().all(|p| p.z == 0.0);
        let spline = dxf::entities::Spline {
            degree_of_curve: f.degree as i32,
            knot_values: f.knots.clone(),
            weight_values: f.weights.clone().unwrap_or_default(),
            control_points: f.points.iter().map(|p| Point::new(p.x, p.y, p.z)).collect(),
            flags: if f.weights.is_some() { 4 } else { 0 } | if planar { 8 } else { 0 },
            normal: dxf::Vector::new(0.0, 0.0, 1.0),
            ..Default::default()
        };
        let mut e = Entity::new(EntityType::Spline(spline));
        e.common.layer = name;
        e.common.color_24_bit = rgb;
        d.add_entity(e);
    }
    d
}
